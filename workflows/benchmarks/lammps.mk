# LAMMPS yardstick of the benchmarks. `make lammps` installs Debian's lammps
# (with its MPI launcher and GNU time) if missing, writes the crack-branching plate inputs for
# peri/lps and peri/pmb, runs each at 1 and 2 MPI ranks and writes $(OUT)/lammps.csv.
# Included by workflows/benchmarks/Makefile: set OUT there *before* the include (default: out).
# Knobs: LAMMPS_RANKS (default 1,2), LAMMPS_REPEATS (runs of each, default 3: the fastest is
# kept), LAMMPS_MPIRUN_ARGS (e.g. --bind-to none),
# LAMMPS_PLATE_ARGS (generator options, e.g. "--nx 40 --ny 20 --steps 50" for a smoke test).

LAMMPS_BENCH_DIR          := $(abspath $(dir $(lastword $(MAKEFILE_LIST))))/lammps
LAMMPS_SAVED_DEFAULT_GOAL := $(.DEFAULT_GOAL)

OUT                ?= out
LAMMPS_PYTHON      ?= /usr/bin/python3
LAMMPS_RANKS       ?= 1,2
LAMMPS_REPEATS     ?= 3
LAMMPS_MPIRUN_ARGS ?=
LAMMPS_PLATE_ARGS  ?=
LAMMPS_PACKAGES    := lammps openmpi-bin time
LAMMPS_INPUTS      := $(OUT)/lammps

.PHONY: lammps lammps-deps lammps-inputs

lammps: $(OUT)/lammps.csv

# Idempotent, like `make -C workflows deps`: installs only what dpkg says is missing.
lammps-deps:
	$(call install_missing,$(LAMMPS_PACKAGES))

lammps-inputs: $(LAMMPS_INPUTS)/plate.json

# plate.json is written last, after in.plate-lps and in.plate-pmb.
$(LAMMPS_INPUTS)/plate.json: $(LAMMPS_BENCH_DIR)/make_plate_input.py
	$(LAMMPS_PYTHON) $< --out-dir $(LAMMPS_INPUTS) $(LAMMPS_PLATE_ARGS)

# The runner appends to a fresh temporary CSV that is renamed at the end, so an interrupted
# run never leaves a partial lammps.csv behind.
$(OUT)/lammps.csv: $(LAMMPS_INPUTS)/plate.json $(LAMMPS_BENCH_DIR)/run_lammps.py | lammps-deps
	@rm -f $@.tmp
	$(LAMMPS_PYTHON) $(LAMMPS_BENCH_DIR)/run_lammps.py $@.tmp --inputs $(LAMMPS_INPUTS) \
	  --ranks $(LAMMPS_RANKS) --repeats $(LAMMPS_REPEATS) $(if $(LAMMPS_MPIRUN_ARGS),--mpirun-args="$(LAMMPS_MPIRUN_ARGS)")
	mv $@.tmp $@

# The 3-D block (make_block_input.py: 60^3 points, horizon 2.05 dx, 100 steps), the yardstick of
# mppm's 3-D kernels: `make lammps-3d` -> $(OUT)/lammps_block.csv. Knobs: LAMMPS_BLOCK_ARGS
# (generator options, e.g. "--n 12 --steps 10" for a smoke test).
LAMMPS_BLOCK_ARGS ?=
LAMMPS_BLOCK_INPUTS := $(OUT)/lammps-block
.PHONY: lammps-3d
lammps-3d: $(OUT)/lammps_block.csv

$(LAMMPS_BLOCK_INPUTS)/block.json: $(LAMMPS_BENCH_DIR)/make_block_input.py $(LAMMPS_BENCH_DIR)/make_plate_input.py
	$(LAMMPS_PYTHON) $< --out-dir $(LAMMPS_BLOCK_INPUTS) $(LAMMPS_BLOCK_ARGS)

$(OUT)/lammps_block.csv: $(LAMMPS_BLOCK_INPUTS)/block.json $(LAMMPS_BENCH_DIR)/run_lammps.py | lammps-deps
	@rm -f $@.tmp
	$(LAMMPS_PYTHON) $(LAMMPS_BENCH_DIR)/run_lammps.py $@.tmp --benchmark block --inputs $(LAMMPS_BLOCK_INPUTS) \
	  --ranks $(LAMMPS_RANKS) --repeats $(LAMMPS_REPEATS) $(if $(LAMMPS_MPIRUN_ARGS),--mpirun-args="$(LAMMPS_MPIRUN_ARGS)")
	mv $@.tmp $@

# Including this fragment must not change the including Makefile's default goal.
.DEFAULT_GOAL := $(LAMMPS_SAVED_DEFAULT_GOAL)
