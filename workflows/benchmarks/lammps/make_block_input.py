#!/usr/bin/python3
"""Writes the LAMMPS PERI inputs of the 3-D block benchmark (mppm's 3-D yardstick).

Owns: a simple-cubic block of NX x NY x NZ points (default 60^3 = 216 000, dx = 1 mm, horizon
factor 2.05: 30 bonds per interior point, the lattice of mppm's 3-D block benchmark) as LAMMPS
`peri/lps` and `peri/pmb` inputs, with the same family rule as mppm (|xi| <= delta + 1e-9 dx) and
the exact bond count the runner checks LAMMPS against. Standard library only; run with
/usr/bin/python3.

Outputs in --out-dir (each written to a temporary name, then renamed):
  in.block-lps, in.block-pmb   LAMMPS inputs
  block.json                   points, bonds (both ends), steps and the derived constants
                               (the schema of make_plate_input.py's plate.json: run_lammps.py
                               --benchmark block reads it)

Conversions (3-D, no plane-strain mapping): peri/lps takes the bulk modulus K = lambda + 2 mu / 3
and the shear modulus G = mu as they are (its formulas are the 3-D state-based ones); peri/pmb
takes c = 18 K / (pi delta^4), the bond-based micromodulus of a 3-D continuum family, exact for
nu = 1/4 (lambda = mu), the block's material. The density is the skeleton's partial density
phi_s rho_s, as mppm uses.
"""

import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from make_plate_input import FAMILY_TOLERANCE_IN_SPACINGS, PREAMBLE, material_and_run, positive  # noqa: E402
from mppm_outputs import write_text  # noqa: E402
from script_exit import InputError  # noqa: E402


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description="Write LAMMPS peri/lps and peri/pmb inputs of the 3-D block benchmark.")
    parser.add_argument("--out-dir", required=True, help="directory for the inputs and block.json")
    parser.add_argument("--models", default="lps,pmb", help="comma-separated subset of lps,pmb (default: lps,pmb)")
    parser.add_argument("--n", type=int, default=60, help="points along each edge (default 60: 216 000 points)")
    parser.add_argument("--spacing", type=float, default=1e-3, help="dx [m] (default 1e-3)")
    parser.add_argument("--horizon-factor", type=float, default=2.05, help="delta / dx (default 2.05)")
    parser.add_argument("--lambda", dest="lame_lambda", type=float, default=14e9, help="Lame lambda [Pa] (default 14e9)")
    parser.add_argument("--mu", type=float, default=14e9, help="shear modulus mu [Pa] (default 14e9)")
    parser.add_argument("--density", type=float, default=2650.0, help="grain density rho_s [kg/m3] (default 2650)")
    parser.add_argument("--solid-fraction", type=float, default=0.95, help="phi_s; LAMMPS gets phi_s rho_s")
    parser.add_argument("--time-step", type=float, default=5e-8, help="dt [s] (default 5e-8, the block scene's)")
    parser.add_argument("--steps", type=int, default=100, help="time steps (default 100)")
    parser.add_argument("--critical-stretch", type=float, default=1.0,
                        help="LAMMPS s00; far above any stretch of the run so no bond breaks (default 1.0)")
    parser.add_argument("--strain-rate", type=float, default=5.0,
                        help="initial vertical velocity gradient dv_y/dy [1/s], so every bond is stretched")
    parser.add_argument("--thermo-every", type=int, default=1000, help="thermo output interval in steps")
    args = parser.parse_args(argv)
    models = [m.strip() for m in args.models.split(",") if m.strip()]
    if not models or any(m not in ("lps", "pmb") for m in models):
        raise InputError(f"--models: expected lps and/or pmb (got {args.models})")
    args.models = models
    for name in ("n", "steps", "thermo_every"):
        if getattr(args, name) < 1:
            raise InputError(f"--{name.replace('_', '-')}: must be a positive integer (got {getattr(args, name)})")
    for name in ("spacing", "horizon_factor", "mu", "density", "solid_fraction", "time_step", "critical_stretch"):
        positive(name.replace("_", "-"), getattr(args, name))
    if args.solid_fraction > 1.0:
        raise InputError(f"--solid-fraction: must be in (0, 1] (got {args.solid_fraction})")
    if not (args.lame_lambda + 2.0 * args.mu / 3.0 > 0.0):
        raise InputError("--lambda/--mu: the bulk modulus lambda + 2 mu / 3 must be positive")
    return args


def count_bonds(n, horizon_factor):
    """Sum over the points of the family size (each bond counted from both ends), as mppm counts:
    the pairs at lattice offset (a, b, c) number (n - |a|)(n - |b|)(n - |c|)."""
    reach = horizon_factor + FAMILY_TOLERANCE_IN_SPACINGS
    span = int(math.floor(reach))
    bonds = 0
    for a in range(-span, span + 1):
        for b in range(-span, span + 1):
            for c in range(-span, span + 1):
                if (a, b, c) != (0, 0, 0) and a * a + b * b + c * c <= reach * reach:
                    bonds += max(n - abs(a), 0) * max(n - abs(b), 0) * max(n - abs(c), 0)
    return bonds


def lammps_input(args, model, constants):
    dx, n = args.spacing, args.n
    return f"""\
# 3-D block benchmark, LAMMPS peri/{model} yardstick of mppm's 3-D block.
# Generated by workflows/benchmarks/lammps/make_block_input.py; edit the generator, not this file.
# {n}^3 points, dx = {dx:g} m, delta = {args.horizon_factor:g} dx, {constants['points']} points,
# {constants['bonds']} bonds (both ends), {args.steps} steps.

{PREAMBLE}
lattice         sc {dx:.17g} origin 0.5 0.5 0.5
region          box block -2 {n + 2} -2 {n + 2} -2 {n + 2}
create_box      1 box
region          block block 0 {n} 0 {n} 0 {n}
create_atoms    1 region block

""" + material_and_run(args, model, constants, n * dx)


def main(argv):
    try:
        args = parse_arguments(argv)
        if os.path.exists(args.out_dir) and not os.path.isdir(args.out_dir):
            raise InputError(f"--out-dir: {args.out_dir} exists and is not a directory")
        os.makedirs(args.out_dir, exist_ok=True)
    except InputError as error:
        print(f"make_block_input.py: {error}", file=sys.stderr)
        return 2
    delta = args.horizon_factor * args.spacing
    bulk = args.lame_lambda + 2.0 * args.mu / 3.0
    constants = {
        "points": args.n ** 3,
        "bonds": count_bonds(args.n, args.horizon_factor),
        "cut": delta + FAMILY_TOLERANCE_IN_SPACINGS * args.spacing,
        "volume": args.spacing ** 3,
        "density": args.solid_fraction * args.density,
        "bulk_modulus": bulk,
        "shear_modulus": args.mu,
        "micromodulus": 18.0 * bulk / (math.pi * delta ** 4),
    }
    summary = {
        "case": f"3-D block, {args.n}^3 points (workflows/benchmarks/README.md)",
        "points": constants["points"], "bonds": constants["bonds"], "steps": args.steps, "n": args.n,
        "spacing_m": args.spacing, "horizon_factor": args.horizon_factor, "horizon_m": delta,
        "lammps_cut_m": constants["cut"], "time_step_s": args.time_step,
        "lambda_Pa": args.lame_lambda, "mu_Pa": args.mu, "density_kg_per_m3": constants["density"],
        "volume_m3": constants["volume"], "models": {},
    }
    try:
        for model in args.models:
            name = f"in.block-{model}"
            write_text(os.path.join(args.out_dir, name), lammps_input(args, model, constants))
            entry = {"input": name, "effects": f"peri/{model}", "case": f"block-lammps-{model}"}
            if model == "lps":
                entry.update(bulk_modulus_Pa=bulk, shear_modulus_Pa=args.mu)
            else:
                entry.update(micromodulus_N_per_m6=constants["micromodulus"])
            summary["models"][model] = entry
        write_text(os.path.join(args.out_dir, "block.json"), json.dumps(summary, indent=2) + "\n")
    except OSError as error:
        print(f"make_block_input.py: cannot write into {args.out_dir}: {error}", file=sys.stderr)
        return 1
    print(f"wrote {', '.join('in.block-' + m for m in args.models)} and block.json in {args.out_dir}: "
          f"{constants['points']} points, {constants['bonds']} bonds ({constants['bonds'] / constants['points']:.2f} per point)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
