"""Reading the accuracy-cost CSV and the fits both report.py and check.py use."""
import csv
import math

# Rates the scheme should show at a fixed horizon factor (derived in README.md):
# waves: nonlocal dispersion O((k delta)^2) plus central-difference O((W dt)^2), dt ~ dx;
# cut-off: exact in space, central differences only; layer: faces smeared over O(delta / h).
# crack: the work of each bond's last step before it breaks, O(dt) at a fixed dx / dt ratio
# and, at a fixed safety factor, the same share of w_cr at every spacing (the tip crosses a
# horizon in a fixed number of steps): rate 0 in dx, rate 1 in the safety factor.
# terzaghi: the drained layer acts as a face 0.81 dx beyond the body's, an error O(dx / H) in U
# and in the base pressure, above a floor set by the quasi-static run's lag (README.md).
EXPECTED_RATE = {"p_wave": 2.0, "shear_rotation_wave": 2.0, "cutoff_frequency": 2.0, "layer_shear": 1.0,
                 "crack_energy": 0.0, "terzaghi": 1.0}
# Bond updates ~ dx^-COST_EXPONENT at a fixed horizon factor: d + 1 for the lattices refined in
# every direction; the Terzaghi column is 8 points across whatever dx (a 1-D problem): its points
# grow like dx^-1 and its steps like dx^-1.
COST_EXPONENT = {"terzaghi": 2.0}
# The pore-fluid test's tolerances on its 80-row column (tests/verification/
# test_solver_pore_fluid_boundaries.cpp): |U - series| <= 0.02 and |p_base / p0 - series| <= 0.03
# for T_v in [0.1, 1].
TERZAGHI_TEST_ROWS = 80
TERZAGHI_TOLERANCE = {"error": 0.02, "second_error": 0.03}
# The distance beyond the body's top at which the drained layer's pressure acts, in dx, at horizon
# factor 3.05 (measured by the test's steady Darcy flow between two drained faces): the column
# drains as one a taller, which lowers U by about a / H at T_v = 0.1.
TERZAGHI_FACE_OFFSET = 0.8144
EXPECTED_SAFETY_RATE = {"crack_energy": 1.0}
NUMBERS = ("spacing_m", "horizon_factor", "safety", "stabilization", "error", "signed_error", "measured", "analytic", "load_average",
           "time_step_s", "setup_seconds", "wall_seconds", "bond_updates", "bond_updates_per_second", "second_error")
INTEGERS = ("dimension", "resolution", "threads", "points", "bonds", "steps", "peak_memory_bytes")


def load(path):
    """All rows; numeric cells converted (empty cells: None)."""
    rows = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            for key in NUMBERS:
                row[key] = float(row[key]) if row.get(key) else None
            for key in INTEGERS:
                row[key] = int(float(row[key])) if row.get(key) else None
            rows.append(row)
    return rows


def ok(rows):
    return [r for r in rows if r["status"] == "ok"]


def least_squares_slope(xs, ys):
    """Slope of y = a + b x."""
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx


def log_slope(rows, x_key, y_key):
    """Least-squares slope of log y against log x."""
    return least_squares_slope([math.log(r[x_key]) for r in rows], [math.log(r[y_key]) for r in rows])


def spacing_groups(rows):
    """{(problem, dimension, threads): rows of the spacing sweep, coarsest first}."""
    groups = {}
    for r in ok(rows):
        if r["sweep"] == "spacing":
            groups.setdefault((r["problem"], r["dimension"], r["threads"]), []).append(r)
    for group in groups.values():
        group.sort(key=lambda r: r["resolution"])
    return groups


def cost_exponent(problem, dimension):
    """The expected p of bond updates ~ dx^-p over a spacing sweep."""
    return COST_EXPONENT.get(problem, dimension + 1.0)


def label(problem, dimension):
    names = {"p_wave": "P wave", "shear_rotation_wave": "shear-rotation wave", "cutoff_frequency": "cut-off frequency",
             "layer_shear": "Cosserat layer in shear", "crack_energy": "energy per crack area",
             "terzaghi": "Terzaghi consolidation"}
    return f"{names.get(problem, problem)} ({dimension}-D)"
