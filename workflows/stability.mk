# Stability report, included by workflows/Makefile (`include stability.mk`):
#   make -C workflows stability-report   runs every stability case (short forms and the long
#                                        forms, 10^5 steps) and regenerates the margins table
#                                        of tests/stability/README.md from the measured results
# Uses ROOT, BUILD and the `build` target of workflows/Makefile (defaults below when used on
# its own, then the build directory must already be built).

ROOT  ?= $(abspath $(dir $(lastword $(MAKEFILE_LIST)))/..)
BUILD ?= $(ROOT)/build
STABILITY_RECORDS := $(BUILD)/stability

.PHONY: stability-report stability-run

# The records of an earlier run are removed first, so the table holds only this run's numbers.
# The table is rendered even when a case fails (its row then says so), and the target fails.
stability-run: build
	rm -rf $(STABILITY_RECORDS)
	cd $(BUILD) && ctest --output-on-failure -L stability --timeout 3600; echo $$? > $(BUILD)/stability-ctest-status

stability-report: stability-run
	/usr/bin/python3 $(ROOT)/tests/stability/render_margins.py $(ROOT)/tests/stability/README.md \
	  $(STABILITY_RECORDS)/short $(STABILITY_RECORDS)/long
	@status=$$(cat $(BUILD)/stability-ctest-status); [ "$$status" = 0 ] || { echo "stability: ctest failed ($$status)"; exit 1; }
