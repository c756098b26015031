#!/usr/bin/python3
"""Writes the LAMMPS PERI inputs of the crack-branching plate benchmark (mppm's yardstick).

Owns: the translation of the crack-branching plate (lattice, horizon, material, time step) into LAMMPS
`peri/lps` and `peri/pmb` inputs, the moduli conversions, and the bond count that the runner
checks LAMMPS against. Standard library only; run with /usr/bin/python3.

Outputs in --out-dir (each written to a temporary name, then renamed):
  in.plate-lps, in.plate-pmb   LAMMPS inputs
  plate.json                   points, bonds (both ends), steps and the derived constants

Conventions and conversions (see workflows/benchmarks/README.md for the derivations):
- Points: NX x NY lattice at (i + 1/2) dx, (j + 1/2) dx, one layer z = 0 in a 3-D LAMMPS box
  (`lattice sc dx`: LAMMPS PERI requires a cubic lattice constant, which it also uses for its
  partial-volume weights near the horizon). Volume of each point dx^2 t.
- Family: LAMMPS keeps j as a partner when |xi|^2 <= cut^2 (fix PERI_NEIGH). We pass
  cut = delta + 1e-9 dx, the same tolerance mppm uses, so both codes hold the same families.
- Density: LAMMPS PERI treats the per-atom mass as a density; we give the skeleton partial
  density phi_s rho_s that mppm uses.
- peri/lps: LAMMPS applies the 3-D LPS formulas (theta = 3/m sum w |xi| e V, force
  (3K - 5G) theta w |xi| / m + 15 G w e / m). On an in-plane family they reproduce the
  plane-strain energy of (lambda, mu) for every homogeneous in-plane strain when
  K = 4 (lambda + mu) / 9 and G = 8 mu / 15.
- peri/pmb: c = 12 (lambda + mu) / (pi t delta^3) (plane-strain bulk modulus lambda + mu,
  2-D family with volumes dx^2 t). Exact for lambda = mu (nu = 1/4, the only Poisson ratio
  a bond-based plane-strain model has), which is the plate's material.
"""

import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from mppm_outputs import write_text  # noqa: E402
from script_exit import InputError  # noqa: E402

# mppm's family tolerance (docs/theory.md section 1): lattice points on the horizon sphere are in.
FAMILY_TOLERANCE_IN_SPACINGS = 1e-9


def positive(name, value):
    if not (value > 0.0 and math.isfinite(value)):
        raise InputError(f"--{name}: must be a positive finite number (got {value})")
    return value


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        description="Write LAMMPS peri/lps and peri/pmb inputs of the crack-branching plate "
                    "(workflows/crack-branching, no notch) for the benchmarks.")
    parser.add_argument("--out-dir", required=True, help="directory for the inputs and plate.json")
    parser.add_argument("--models", default="lps,pmb",
                        help="comma-separated subset of lps,pmb (default: lps,pmb)")
    parser.add_argument("--nx", type=int, default=200, help="points along x (default 200)")
    parser.add_argument("--ny", type=int, default=80, help="points along y (default 80)")
    parser.add_argument("--spacing", type=float, default=0.5e-3, help="dx [m] (default 0.5e-3)")
    parser.add_argument("--horizon-factor", type=float, default=4.05,
                        help="delta / dx (default 4.05)")
    parser.add_argument("--thickness", type=float, default=1e-3,
                        help="plane-strain thickness t [m] (default 1e-3)")
    parser.add_argument("--lambda", dest="lame_lambda", type=float, default=14e9,
                        help="Lame lambda [Pa] (default 14e9)")
    parser.add_argument("--mu", type=float, default=14e9, help="shear modulus mu [Pa] (default 14e9)")
    parser.add_argument("--density", type=float, default=2650.0,
                        help="grain density rho_s [kg/m3] (default 2650)")
    parser.add_argument("--solid-fraction", type=float, default=0.95,
                        help="phi_s; LAMMPS gets phi_s rho_s (default 0.95)")
    parser.add_argument("--time-step", type=float, default=2.5e-8, help="dt [s] (default 2.5e-8)")
    parser.add_argument("--steps", type=int, default=2000, help="time steps (default 2000)")
    parser.add_argument("--critical-stretch", type=float, default=1.0,
                        help="LAMMPS s00; far above any stretch of the run so no bond breaks "
                             "(default 1.0)")
    parser.add_argument("--strain-rate", type=float, default=5.0,
                        help="initial vertical velocity gradient dv_y/dy [1/s] so that every bond "
                             "is stretched (default 5: strain ~ rate * steps * dt = 2.5e-4)")
    parser.add_argument("--thermo-every", type=int, default=1000,
                        help="thermo output interval in steps (default 1000: sparse)")
    args = parser.parse_args(argv)

    models = [m.strip() for m in args.models.split(",") if m.strip()]
    unknown = [m for m in models if m not in ("lps", "pmb")]
    if not models or unknown:
        raise InputError(f"--models: unknown model(s) {unknown or models} (expected lps and/or pmb)")
    args.models = models
    for name in ("nx", "ny", "steps", "thermo_every"):
        if getattr(args, name) < 1:
            raise InputError(f"--{name.replace('_', '-')}: must be a positive integer "
                             f"(got {getattr(args, name)})")
    for name in ("spacing", "horizon_factor", "thickness", "mu", "density", "solid_fraction",
                 "time_step", "critical_stretch"):
        positive(name.replace("_", "-"), getattr(args, name))
    if args.solid_fraction > 1.0:
        raise InputError(f"--solid-fraction: must be in (0, 1] (got {args.solid_fraction})")
    if not (args.lame_lambda + args.mu > 0.0):
        raise InputError("--lambda/--mu: the plane-strain bulk modulus lambda + mu must be positive")
    if not (args.strain_rate >= 0.0 and math.isfinite(args.strain_rate)):
        raise InputError(f"--strain-rate: must be >= 0 (got {args.strain_rate})")
    return args


def count_bonds(nx, ny, horizon_factor):
    """Sum over points of the family size (each bond counted from both ends), as mppm counts.

    On a regular lattice the pairs at offset (a, b) number (nx - |a|)(ny - |b|), so the count is
    exact and needs no point loop."""
    reach = horizon_factor + FAMILY_TOLERANCE_IN_SPACINGS
    span = int(math.floor(reach))
    bonds = 0
    for a in range(-span, span + 1):
        for b in range(-span, span + 1):
            if (a, b) == (0, 0) or a * a + b * b > reach * reach:
                continue
            bonds += max(nx - abs(a), 0) * max(ny - abs(b), 0)
    return bonds


def lps_moduli(lame_lambda, mu):
    """K, G for LAMMPS's 3-D LPS formulas on an in-plane family that give plane-strain (lambda, mu).

    For a homogeneous in-plane strain eps the LAMMPS energy density is
    (9K/8)(tr eps)^2 + (15G/4) d^2 with d^2 = (eps_xx - eps_yy)^2/4 + eps_xy^2; plane strain is
    ((lambda + mu)/2)(tr eps)^2 + 2 mu d^2."""
    return 4.0 * (lame_lambda + mu) / 9.0, 8.0 * mu / 15.0


def pmb_micromodulus(lame_lambda, mu, thickness, delta):
    """c of LAMMPS peri/pmb from the plane-strain bulk modulus lambda + mu.

    Energy density of an isotropic stretch s: (1/4) c s^2 t int_0^delta xi 2 pi xi dxi
    = pi c t delta^3 s^2 / 6, equal to 2 (lambda + mu) s^2."""
    return 12.0 * (lame_lambda + mu) / (math.pi * thickness * delta ** 3)


# The first commands of every input (PERI wants a 3-D box even for the one-layer plate).
PREAMBLE = """\
units           si
dimension       3
boundary        f f f
atom_style      peri
atom_modify     map array
"""


def pair_lines(args, model, constants):
    """The pair style and coefficients of peri/lps or peri/pmb (s00 far above any stretch, alpha 0)."""
    if model == "lps":
        return (f"pair_style      peri/lps\n"
                f"pair_coeff      * * {constants['bulk_modulus']:.17g} "
                f"{constants['shear_modulus']:.17g} {constants['cut']:.17g} "
                f"{args.critical_stretch:.17g} 0.0\n")
    return (f"pair_style      peri/pmb\n"
            f"pair_coeff      * * {constants['micromodulus']:.17g} {constants['cut']:.17g} "
            f"{args.critical_stretch:.17g} 0.0\n")


def material_and_run(args, model, constants, height):
    """The input after the lattice (shared with make_block_input.py): the pair style, density and
    volume, the set-up run, the stretching velocity ramp over `height`, the integrator and the run."""
    dx = args.spacing
    velocity = 0.5 * args.strain_rate * height
    return f"""\
# s00 far above any stretch of the run (no bond breaks); alpha = 0
{pair_lines(args, model, constants)}set             group all density {constants['density']:.17g}
set             group all volume {constants['volume']:.17g}

# Set-up run: builds the bond families and sets every point's critical stretch s0. Without it
# the first step would read s0 before it is ever set (the families do not exist yet during the
# first force computation) and break the stretched bonds of the moving plate at once.
run             0 post no

# a uniform vertical stretching rate, so every bond does real arithmetic
velocity        all ramp vy {-velocity:.17g} {velocity:.17g} y 0.0 {height:.17g} units box sum no

# short skin: the run barely moves, and the half list also drives PERI's contact loop
neighbor        {0.25 * dx:.17g} bin
neigh_modify    every 1 delay 0 check yes

fix             integrate all nve
timestep        {args.time_step:.17g}

compute         damage all damage/atom
compute         max_damage all reduce max c_damage
thermo_style    custom step ke pe etotal c_max_damage
thermo_modify   format float %.10g
thermo          {args.thermo_every}
run             {args.steps}
"""


def lammps_input(args, model, constants):
    dx = args.spacing
    return f"""\
# Crack-branching plate of workflows/crack-branching (no notch), LAMMPS peri/{model} yardstick of the benchmarks.
# Generated by workflows/benchmarks/lammps/make_plate_input.py; edit the generator, not this file.
# {args.nx} x {args.ny} points, dx = {dx:g} m, delta = {args.horizon_factor:g} dx, t = {args.thickness:g} m,
# {constants['points']} points, {constants['bonds']} bonds (both ends), {args.steps} steps.

{PREAMBLE}
# one layer of a cubic lattice: PERI needs xlattice = ylattice = zlattice = dx
lattice         sc {dx:.17g} origin 0.5 0.5 0.0
region          box block -2 {args.nx + 2} -2 {args.ny + 2} -0.5 0.5
create_box      1 box
region          plate block 0 {args.nx} 0 {args.ny} -0.5 0.5
create_atoms    1 region plate

""" + material_and_run(args, model, constants, args.ny * dx)


def main(argv):
    try:
        args = parse_arguments(argv)
        out_dir = args.out_dir
        if os.path.exists(out_dir) and not os.path.isdir(out_dir):
            raise InputError(f"--out-dir: {out_dir} exists and is not a directory")
        os.makedirs(out_dir, exist_ok=True)
    except InputError as error:
        print(f"make_plate_input.py: {error}", file=sys.stderr)
        return 2
    except OSError as error:
        print(f"make_plate_input.py: --out-dir: cannot create {args.out_dir}: {error}",
              file=sys.stderr)
        return 2

    if args.lame_lambda != args.mu:
        print("make_plate_input.py: warning: lambda != mu; peri/pmb (bond-based, nu = 1/4 in plane "
              "strain) matches only the bulk modulus lambda + mu", file=sys.stderr)

    delta = args.horizon_factor * args.spacing
    bulk, shear = lps_moduli(args.lame_lambda, args.mu)
    constants = {
        "points": args.nx * args.ny,
        "bonds": count_bonds(args.nx, args.ny, args.horizon_factor),
        "delta": delta,
        "cut": delta + FAMILY_TOLERANCE_IN_SPACINGS * args.spacing,
        "volume": args.spacing ** 2 * args.thickness,
        "density": args.solid_fraction * args.density,
        "bulk_modulus": bulk,
        "shear_modulus": shear,
        "micromodulus": pmb_micromodulus(args.lame_lambda, args.mu, args.thickness, delta),
    }
    summary = {
        "case": "crack-branching plate (workflows/crack-branching/README.md), no notch",
        "points": constants["points"],
        "bonds": constants["bonds"],
        "steps": args.steps,
        "nx": args.nx, "ny": args.ny,
        "spacing_m": args.spacing,
        "horizon_factor": args.horizon_factor,
        "horizon_m": delta,
        "lammps_cut_m": constants["cut"],
        "thickness_m": args.thickness,
        "time_step_s": args.time_step,
        "lambda_Pa": args.lame_lambda, "mu_Pa": args.mu,
        "density_kg_per_m3": constants["density"],
        "volume_m3": constants["volume"],
        "models": {},
    }
    try:
        for model in args.models:
            name = f"in.plate-{model}"
            write_text(os.path.join(out_dir, name), lammps_input(args, model, constants))
            entry = {"input": name, "effects": f"peri/{model}", "case": f"plate-lammps-{model}"}
            if model == "lps":
                entry.update(bulk_modulus_Pa=bulk, shear_modulus_Pa=shear)
            else:
                entry.update(micromodulus_N_per_m6=constants["micromodulus"])
            summary["models"][model] = entry
        write_text(os.path.join(out_dir, "plate.json"), json.dumps(summary, indent=2) + "\n")
    except OSError as error:
        print(f"make_plate_input.py: cannot write into {out_dir}: {error}", file=sys.stderr)
        return 1
    print(f"wrote {', '.join('in.plate-' + m for m in args.models)} and plate.json in {out_dir}: "
          f"{constants['points']} points, {constants['bonds']} bonds "
          f"({constants['bonds'] / constants['points']:.2f} per point)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
