# Shared rules of a case folder: points -> run -> post -> check, with real file dependencies
# so `make` reruns only stale stages. A case Makefile sets SCENE (and optionally RUN_ARGS,
# POST_ARGS) and includes this file.
ROOT     := $(abspath $(dir $(lastword $(MAKEFILE_LIST)))/..)
MPPM_BIN ?= $(ROOT)/build/bin
OUT      ?= out
SCENE    ?= scene.yaml
THREADS  ?= $(shell nproc 2>/dev/null || echo 2)
GEOMETRY := $(shell sed -n 's/^ *file: *\([^ #]*\).*/\1/p' $(SCENE) | head -1)

$(OUT)/points.vtp: $(SCENE) $(GEOMETRY) $(MPPM_BIN)/mppm-preprocess
	@mkdir -p $(OUT)
	$(MPPM_BIN)/mppm-preprocess $(SCENE) -o $@ $(PRE_ARGS)

$(OUT)/run/run_info.json: $(OUT)/points.vtp $(SCENE) $(MPPM_BIN)/mppm-solve
	$(MPPM_BIN)/mppm-solve $(SCENE) --points $< -o $(OUT)/run --force --threads $(THREADS) $(RUN_ARGS)

$(OUT)/post/summary.json: $(OUT)/run/run_info.json $(MPPM_BIN)/mppm-postprocess
	$(MPPM_BIN)/mppm-postprocess $(OUT)/run -o $(OUT)/post --force $(POST_ARGS)

.PHONY: points run post figures clean
points: $(OUT)/points.vtp
run: $(OUT)/run/run_info.json
post: $(OUT)/post/summary.json
figures: $(OUT)/run/run_info.json
	$(MPPM_BIN)/mppm-postprocess $(OUT)/run -o $(OUT)/post --figures --force $(POST_ARGS)
clean:
	rm -rf $(OUT)
