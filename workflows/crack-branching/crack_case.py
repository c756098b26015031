"""Shared reading of the crack-branching case outputs (check_case.py, report_case.py)."""
import csv
import json
import math
import os
import xml.etree.ElementTree as ET


def summary(out, run):
    with open(os.path.join(out, run, "post", "summary.json")) as f:
        return json.load(f)


def energy_rows(out, run):
    with open(os.path.join(out, run, "run", "energy.csv"), newline="") as f:
        return list(csv.DictReader(f))


def load_rows(out, run):
    with open(os.path.join(out, run, "run", "load.csv"), newline="") as f:
        return list(csv.DictReader(f))


def frames(out, run):
    """(time, path) of every frame of the run's ParaView series, in time order."""
    post = os.path.join(out, run, "post")
    tree = ET.parse(os.path.join(post, "results.pvd"))
    series = [(float(d.get("timestep")), os.path.join(post, d.get("file"))) for d in tree.iter("DataSet")]
    return sorted(series)


def rayleigh_speed(material):
    """Rayleigh wave speed of the classical (long-wave) elastic solid of the resolved material:
    the root xi = c_R / c_s in (0, 1) of (2 - xi^2)^2 = 4 sqrt(1 - xi^2) sqrt(1 - xi^2 c_s^2 / c_p^2)."""
    rho = material["density"] * material["solid_fraction"]
    lam, mu = material["lambda"], material["mu"]
    cs, cp = math.sqrt(mu / rho), math.sqrt((lam + 2 * mu) / rho)
    k = (cs / cp) ** 2
    f = lambda x: (2 - x * x) ** 2 - 4 * math.sqrt(1 - x * x) * math.sqrt(1 - k * x * x)
    # f < 0 just above the trivial root 0 and up to c_R, f > 0 from there to c_s (f(1) = 1): for
    # Poisson ratios in [0, 0.5) the root lies in [0.87, 0.96] c_s, which [0.5, 1) brackets.
    lo, hi = 0.5, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(mid) < 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi) * cs


def crack_points(path, threshold=0.35):
    """Body points (region 0) with damage >= threshold of one frame: a set of (x, y) rounded to
    a micrometre (the lattice is exact in the files up to round-off)."""
    import meshio  # Debian python3-meshio, under /usr/bin/python3
    m = meshio.read(path)
    region = m.point_data["region"]
    damage = m.point_data["damage"]
    return {(round(p[0], 6), round(p[1], 6)) for p, r, d in zip(m.points, region, damage) if r == 0 and d >= threshold}
