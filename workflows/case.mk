# What the case folders share: paths, binaries and conventions, and the rules of the stages
# points -> run -> post with real file dependencies, so `make` reruns only stale stages.
#
# Every case folder: ROOT (the repository), HERE (the case folder), MPPM_BIN (the executables),
# PYTHON (/usr/bin/python3, which has meshio, matplotlib and yaml), OUT (output folder),
# THREADS (solver threads; default all cores), SET (extra `--set key=value` overrides;
# SET_ARGS is them as options).
#
# A case with a scene sets SCENE (and optionally PRE_ARGS, the preprocessor's extra options)
# before including this file; the scene's geometry file is a dependency of its points. Then:
#   one run  (RUNS unset): $(OUT)/points.vtp, $(OUT)/run/, $(OUT)/post/ with RUN_ARGS and
#            POST_ARGS; targets points, run, post, figures, clean;
#   many runs (RUNS set):  one points file $(OUT)/points.vtp, and per run $(OUT)/<run>/ with a
#            copy of it (a run folder stands on its own), run/ and post/. The case defines, for
#            a run name $(1): run_threads (default THREADS), run_args (solver options after
#            --threads) and post_args (postprocessor options after --quiet); run_scene (default
#            SCENE) if some runs solve another scene (their points come from the case's own
#            rule for $(OUT)/<run>/points.vtp). A case may also
#            define announce (a line printed before a stage) and stage (how a stage's command
#            runs: $(call stage,NAME,COMMAND), default the command itself), and STAGE_ECHO (@
#            to hide the commands).
ROOT     := $(abspath $(dir $(lastword $(MAKEFILE_LIST)))/..)
HERE     := $(abspath $(dir $(firstword $(MAKEFILE_LIST))))
MPPM_BIN ?= $(ROOT)/build/bin
PYTHON   ?= /usr/bin/python3
OUT      ?= out
THREADS  ?= $(shell nproc 2>/dev/null || echo 2)
SET      ?=
SET_ARGS  = $(SET:%=--set %)

ifneq ($(SCENE),)
# The first `file:` of the scene, relative to the scene's folder unless absolute.
geometry_entry := $(shell sed -n 's/^ *file: *\([^ #]*\).*/\1/p' $(SCENE) | head -1)
GEOMETRY := $(if $(filter /%,$(geometry_entry)),$(geometry_entry),$(abspath $(dir $(SCENE))$(geometry_entry)))

stage     = $(2)
announce  =
run_threads = $(THREADS)

$(OUT)/points.vtp: $(SCENE) $(GEOMETRY) $(MPPM_BIN)/mppm-preprocess
	@mkdir -p $(OUT)
	$(call announce,mppm-preprocess -> $@)
	$(STAGE_ECHO)$(call stage,points,$(MPPM_BIN)/mppm-preprocess $(SCENE) -o $@ $(PRE_ARGS))

.PHONY: clean
clean:
	rm -rf $(OUT)

ifeq ($(RUNS),)
$(OUT)/run/run_info.json: $(OUT)/points.vtp $(SCENE) $(MPPM_BIN)/mppm-solve
	$(MPPM_BIN)/mppm-solve $(SCENE) --points $< -o $(OUT)/run --force --threads $(THREADS) $(RUN_ARGS)

$(OUT)/post/summary.json: $(OUT)/run/run_info.json $(MPPM_BIN)/mppm-postprocess
	$(MPPM_BIN)/mppm-postprocess $(OUT)/run -o $(OUT)/post --force $(POST_ARGS)

.PHONY: points run post figures
points: $(OUT)/points.vtp
run: $(OUT)/run/run_info.json
post: $(OUT)/post/summary.json
figures: $(OUT)/run/run_info.json
	$(MPPM_BIN)/mppm-postprocess $(OUT)/run -o $(OUT)/post --figures --force $(POST_ARGS)
else
# Each run gets a copy of the shared points file, so a run folder stands on its own.
$(OUT)/%/points.vtp: $(OUT)/points.vtp
	@mkdir -p $(@D)
	@cp $< $@

run_scene ?= $(SCENE)
# The run's scene is a prerequisite named by run_scene, expanded per run (secondary expansion).
.SECONDEXPANSION:
$(OUT)/%/run/run_info.json: $(OUT)/%/points.vtp $$(call run_scene,$$*) $(MPPM_BIN)/mppm-solve
	$(call announce,mppm-solve $* -> $(OUT)/$*/run)
	$(STAGE_ECHO)$(call stage,solve-$*,$(MPPM_BIN)/mppm-solve $(call run_scene,$*) --points $< -o $(OUT)/$*/run \
	  --force --quiet --threads $(call run_threads,$*) $(call run_args,$*))

$(OUT)/%/post/summary.json: $(OUT)/%/run/run_info.json $(MPPM_BIN)/mppm-postprocess
	$(call announce,mppm-postprocess $* -> $(OUT)/$*/post)
	$(STAGE_ECHO)$(call stage,post-$*,$(MPPM_BIN)/mppm-postprocess $(OUT)/$*/run -o $(OUT)/$*/post --force --quiet \
	  $(call post_args,$*))

# No file of a run is an intermediate to delete (make would remove the run's points.vtp and
# run_info.json, which pattern rules alone reach).
.SECONDARY:

.PHONY: points
points: $(OUT)/points.vtp
endif
endif
