# Reliability targets, included by workflows/Makefile (`include reliability.mk`):
#   make -C workflows fuzz       libFuzzer targets built with clang in build-fuzz, each run for
#                                FUZZ_SECONDS (default 60); summary in out/fuzz_summary.txt
#   make -C workflows sanitize   the `sanitize` preset (address + undefined behaviour) built in
#                                build-sanitize; runs the unit and verification tests under it
# Uses ROOT, BUILD and JOBS of workflows/Makefile (defaults below when used on its own).

ROOT          ?= $(abspath $(dir $(lastword $(MAKEFILE_LIST)))/..)
JOBS          ?= $(shell nproc 2>/dev/null || echo 2)
FUZZ_PACKAGES := clang libclang-rt-14-dev
FUZZ_BUILD    ?= $(ROOT)/build-fuzz
FUZZ_SECONDS  ?= 60
FUZZ_TARGETS  ?= scene quantity snapshot point_cloud
RELIABILITY_OUT ?= $(ROOT)/out

.PHONY: fuzz fuzz-deps fuzz-build sanitize

# Same idempotent pattern as `deps`: only what is missing is installed (Debian packages).
fuzz-deps:
	$(call install_missing,$(FUZZ_PACKAGES))

# Only the fuzz targets are built in this tree (the rest of the project needs no clang build).
fuzz-build: deps fuzz-deps
	cmake -S $(ROOT) -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DMPPM_FUZZ=ON \
	  -DMPPM_BUILD_TESTS=OFF -DMPPM_BUILD_BENCHMARKS=OFF
	cmake --build $(FUZZ_BUILD) --target fuzzers -j$(JOBS)

fuzz: fuzz-build
	$(ROOT)/tests/fuzz/run_fuzzers.sh $(FUZZ_BUILD) $(RELIABILITY_OUT) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# The preset's build directory is build-sanitize (CMakePresets.json); the time the tests take
# under the sanitizers goes to out/sanitize_summary.txt. Leaks inside gmsh, OpenCASCADE and
# VTK are suppressed (tests/fuzz/lsan_suppressions.txt); ours are still reported.
sanitize: deps
	cd $(ROOT) && cmake --preset sanitize
	cd $(ROOT) && cmake --build --preset sanitize -j$(JOBS)
	@mkdir -p $(RELIABILITY_OUT)
	@cd $(ROOT) && start=$$(date +%s); \
	LSAN_OPTIONS=suppressions=$(ROOT)/tests/fuzz/lsan_suppressions.txt \
	  ctest --preset sanitize -j$(JOBS) --timeout 1800 -O $(RELIABILITY_OUT)/sanitize_ctest.log; status=$$?; \
	end=$$(date +%s); \
	{ echo "# mppm sanitizer run (address + undefined), $$(date -u '+%Y-%m-%d %H:%M UTC'), $(JOBS) jobs"; \
	  grep -E "tests passed|Total Test time" $(RELIABILITY_OUT)/sanitize_ctest.log; \
	  echo "wall seconds (ctest): $$((end - start))"; } > $(RELIABILITY_OUT)/sanitize_summary.txt; \
	cat $(RELIABILITY_OUT)/sanitize_summary.txt; exit $$status
