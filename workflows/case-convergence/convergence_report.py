"""Case-level convergence and cost (README.md), the report and the check of convergence.py's tables.

usage:
  convergence_report.py report RESULTS.md FIGURES CSV...   results.md and one figure per case
  convergence_report.py check [--quick] CSV...             every run timed on an idle machine, every metric
                                                           of the reference level there (--quick: the test
                                                           suite's form, run beside other tests, one level:
                                                           neither is asked)
"""
import csv
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
from convergence import BUSY_FRACTION, CASES, metric_keys  # noqa: E402
from script_exit import InputError, run_main  # noqa: E402


def read_rows(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise InputError(f"{path}: {e.strerror}")
    if not rows:
        raise InputError(f"{path}: no rows")
    for r in rows:
        for k, v in r.items():
            if k != "case":
                r[k] = None if v == "" else float(v)
    return rows


# ------------------------------------------------------------------------------------------ analysis

def series(rows, factor, key):
    """(spacings, values) of one horizon factor, coarse to fine, runs without the metric left out."""
    pts = sorted(((r["spacing_m"], r[key]) for r in rows if r["horizon_factor"] == factor and r[key] is not None),
                 reverse=True)
    return [p[0] for p in pts], [p[1] for p in pts]


def observed_rate(values):
    """The order p from the last three levels (each half the spacing of the one before) when the
    differences keep their sign and shrink; None otherwise (not converging monotonically)."""
    if len(values) < 3:
        return None
    d1, d2 = values[-3] - values[-2], values[-2] - values[-1]
    if d1 == 0.0 or d2 == 0.0 or (d1 > 0) != (d2 > 0) or abs(d2) >= abs(d1):
        return None
    return math.log2(abs(d1) / abs(d2))


# Richardson's extrapolation is trusted for observed orders in this range: below 1 the correction
# (f3 - f2) / (2^p - 1) is more than the last change itself, an extrapolation far beyond the data
# that a pre-asymptotic sequence would make up; above 4 the levels are at round-off or lucky.
RICHARDSON_ORDERS = (1.0, 4.0)


def reference(values):
    """(reference value, how): Richardson's extrapolation of the last two levels with the observed
    order where the sequence converges monotonically at an order in RICHARDSON_ORDERS, else the
    finest level (then the coarser levels' errors are lower bounds when the sequence still moves)."""
    p = observed_rate(values)
    if p is None:
        return values[-1], "finest level"
    if not RICHARDSON_ORDERS[0] <= p <= RICHARDSON_ORDERS[1]:
        return values[-1], f"finest level (converging at order {p:.2f}: not extrapolated)"
    return values[-1] + (values[-1] - values[-2]) / (2.0 ** p - 1.0), f"Richardson (order {p:.2f})"


def relative_error(value, ref):
    return abs(value - ref) / abs(ref) if ref else float("inf")


# -------------------------------------------------------------------------------------------- report

def fmt_value(value, scale):
    return "none" if value is None else f"{value * scale:.4g}"


def case_section(case, rows, figures):
    c = CASES[case]
    own = c["factors"][0]
    lines = [f"## {case}", "", f"![{case}: metric error against wall time](figures/{case}.png)", "",
             f"Scene `{c['scene']}` as written but for the spacing, the horizon factor and the time step (the "
             "scene's, scaled with the spacing: the same Courant number at every level); every run on one thread. "
             f"The reference of each metric comes from the case's own horizon factor ({own:g}): Richardson's "
             "extrapolation where its three levels converge monotonically at an order between 1 and 4, else its "
             "finest level (then a coarser level's error is a lower bound while the metric still moves). Errors "
             "are relative to it.", "",
             "| horizon factor | dx [mm] | points | bonds | steps | step [us] | " +
             " | ".join(f"{label} [{unit}] (error)" for _, label, _, unit in c["metrics"]) +
             " | wall [s] | estimate [s] | peak MiB (estimate) | other CPU [s] |",
             "|" + "---|" * (10 + len(c["metrics"]))]
    refs = {}
    for key, label, scale, unit in c["metrics"]:
        _, values = series(rows, own, key)
        refs[key] = reference(values) if values else (None, "no value")
    for r in sorted(rows, key=lambda r: (c["factors"].index(r["horizon_factor"]), -r["spacing_m"])):
        cells = []
        for key, _, scale, _ in c["metrics"]:
            ref = refs[key][0]
            err = "" if r[key] is None or ref is None else f" ({100 * relative_error(r[key], ref):.2g} %)"
            cells.append(fmt_value(r[key], scale) + err)
        wall = "BUSY: rerun" if r["busy"] else f"{r['wall_seconds']:.3g}"
        lines.append(f"| {r['horizon_factor']:g} | {r['spacing_m'] * 1e3:g} | {int(r['points'])} | {int(r['bonds'])} | "
                     f"{int(r['steps'])} | {r['time_step_s'] * 1e6:.4g} | " + " | ".join(cells) +
                     f" | {wall} | {r['predicted_seconds']:.3g} | {r['peak_mib']:.0f} ({r['predicted_mib']:.0f}) | "
                     f"{r['other_cpu_seconds']:.1f} |")
    timed = [r for r in rows if not r["busy"]]
    if timed:
        ratios = [r["predicted_seconds"] / r["wall_seconds"] for r in timed]
        memory = [r["predicted_mib"] / r["peak_mib"] for r in timed]
        within = sum(1 for q in ratios if abs(q - 1.0) <= 0.3)
        lines += ["", f"`mppm-solve --estimate` against these runs: wall time {min(ratios):.2f} to {max(ratios):.2f} "
                  f"of the measured ({within} of {len(ratios)} within 30 %), peak memory {min(memory):.2f} to "
                  f"{max(memory):.2f} of the measured."]
    lines += ["", "References and observed orders (from the last three levels of each series; 'no' where they do "
              "not converge monotonically):", "",
              "| metric | reference | from | " + " | ".join(f"order at h = {h:g}" for h in c["factors"]) + " |",
              "|" + "---|" * (3 + len(c["factors"]))]
    for key, label, scale, unit in c["metrics"]:
        orders = []
        for h in c["factors"]:
            p = observed_rate(series(rows, h, key)[1])
            orders.append("no" if p is None else f"{p:.2f}")
        ref, how = refs[key]
        lines.append(f"| {label} [{unit}] | {fmt_value(ref, scale)} | {how} | " + " | ".join(orders) + " |")
    lines += ["", "What a 2x finer lattice buys and costs (the case's horizon factor):", "",
              "| dx [mm] -> dx/2 | " + " | ".join(f"{label} change" for _, label, _, _ in c["metrics"]) +
              " | wall time x | bond updates x |", "|" + "---|" * (3 + len(c["metrics"]))]
    own_rows = sorted((r for r in rows if r["horizon_factor"] == own), key=lambda r: -r["spacing_m"])
    for a, b in zip(own_rows, own_rows[1:]):
        changes = []
        for key, _, _, _ in c["metrics"]:
            changes.append("n/a" if a[key] is None or b[key] is None or not a[key]
                           else f"{100 * (b[key] - a[key]) / abs(a[key]):+.2g} %")
        time_ratio = "busy" if a["busy"] or b["busy"] else f"{b['wall_seconds'] / a['wall_seconds']:.2f}"
        updates = (b["bonds"] * b["steps"]) / (a["bonds"] * a["steps"])
        lines.append(f"| {a['spacing_m'] * 1e3:g} -> {b['spacing_m'] * 1e3:g} | " + " | ".join(changes) +
                     f" | {time_ratio} | {updates:.2f} |")
    lines += ["", "The cheapest measured setting within 1 %, 5 % and 10 % of the reference (the reference's own "
              "finest run excluded: its error is zero by construction when it is the reference):", "",
              "| metric | within 1 % | within 5 % | within 10 % |", "|---|---|---|---|"]
    finest = min(r["spacing_m"] for r in own_rows) if own_rows else None
    for key, label, _, unit in c["metrics"]:
        cells = []
        for tol in (0.01, 0.05, 0.10):
            ref, how = refs[key]
            fits = [r for r in rows if r[key] is not None and ref is not None and not r["busy"]
                    and not (how.startswith("finest level") and r["horizon_factor"] == own and r["spacing_m"] == finest)
                    and relative_error(r[key], ref) <= tol]
            best = min(fits, key=lambda r: r["wall_seconds"], default=None)
            cells.append("none measured" if best is None else
                         f"dx {best['spacing_m'] * 1e3:g} mm, h {best['horizon_factor']:g}: {best['wall_seconds']:.3g} s "
                         f"(estimate {best['predicted_seconds']:.3g} s)")
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    plot_case(case, rows, refs, os.path.join(figures, f"{case}.png"))
    return lines + [""]


def plot_case(case, rows, refs, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    c = CASES[case]
    fig, axes = plt.subplots(1, len(c["metrics"]), figsize=(4.2 * len(c["metrics"]), 3.6))
    for ax, (key, label, _, _) in zip(axes, c["metrics"]):
        ref = refs[key][0]
        for h, marker in zip(c["factors"], "os^"):
            pts = [(r["wall_seconds"], 100 * relative_error(r[key], ref), r["spacing_m"]) for r in rows
                   if r["horizon_factor"] == h and r[key] is not None and ref is not None and not r["busy"]]
            pts = [p for p in pts if p[1] > 0]
            if pts:
                ax.loglog([p[0] for p in pts], [p[1] for p in pts], marker=marker, label=f"horizon {h:g} dx")
                for t, e, dx in pts:
                    ax.annotate(f"{dx * 1e3:g}", (t, e), fontsize=7, xytext=(3, 3), textcoords="offset points")
        # The Pareto front: the runs no other run beats in both wall time and error, circled.
        front = [(r["wall_seconds"], 100 * relative_error(r[key], ref)) for r in rows
                 if r[key] is not None and ref is not None and not r["busy"] and relative_error(r[key], ref) > 0]
        front = [p for p in front if not any(q[0] <= p[0] and q[1] <= p[1] and q != p for q in front)]
        if front:
            ax.scatter([p[0] for p in front], [p[1] for p in front], s=160, facecolors="none", edgecolors="k",
                       label="Pareto front")
        ax.set_title(label)
        ax.set_xlabel("wall time, 1 thread [s]")
        ax.set_ylabel("error against the reference [%]")
        ax.grid(alpha=0.3, which="both")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
    fig.suptitle(f"{case}: error against cost (labels: dx in mm; circled: the Pareto front)")
    fig.tight_layout()
    temporary = path + ".part.png"
    fig.savefig(temporary, dpi=100)
    os.replace(temporary, path)
    plt.close(fig)


def report(results, figures, csvs):
    os.makedirs(figures, exist_ok=True)
    lines = ["# Case-level convergence and cost: results", "",
             "Written by `make report` from " + ", ".join(f"`{os.path.basename(p)}`" for p in csvs) +
             " (README.md says how the runs are made). A run during which other processes took more than "
             f"{100 * BUSY_FRACTION:.0f} % of a core is marked BUSY and its wall time is not shown.", ""]
    all_rows = []
    for path in csvs:
        rows = read_rows(path)
        all_rows += rows
        lines += case_section(rows[0]["case"], rows, figures)
    loads = [r["load_before"] for r in all_rows] + [r["load_after"] for r in all_rows]
    lines += [f"Load average at the runs' starts and ends: {min(loads):.2f} to {max(loads):.2f} (one run at a time, "
              f"one thread); other processes' CPU time per run at most "
              f"{max(r['other_cpu_seconds'] for r in all_rows):.1f} s."]
    temporary = results + ".part"
    with open(temporary, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(temporary, results)
    print(f"report: {results}")
    return 0


def check(csvs, quick=False):
    """A missing metric at a coarse level is a result (no band forms on 3 points across it, a crack
    that never branches) and is reported, not failed; the reference level must have every metric."""
    failures = []
    for path in csvs:
        rows = read_rows(path)
        case = rows[0]["case"]
        own = CASES[case]["factors"][0]
        finest = min(r["spacing_m"] for r in rows if r["horizon_factor"] == own)
        for r in rows:
            where = f"{path}: {case} dx {r['spacing_m'] * 1e3:g} mm, h {r['horizon_factor']:g}"
            if r["busy"] and not quick:
                failures.append(f"{where}: timed on a busy machine ({r['other_cpu_seconds']:.1f} CPU s of other work)")
            if not r["wall_seconds"] > 0:
                failures.append(f"{where}: no wall time")
            missing = [k for k in metric_keys(case) if r[k] is None or not math.isfinite(r[k])]
            if not missing:
                continue
            if r["horizon_factor"] == own and r["spacing_m"] == finest and not quick:
                failures.append(f"{where}: the reference level has no {', '.join(missing)}")
            else:
                print(f"note: {where}: no {', '.join(missing)}")
    for f in failures:
        print("FAIL", f)
    print("PASS" if not failures else f"{len(failures)} failure(s)")
    return 0 if not failures else 1


def main(argv):
    if len(argv) >= 4 and argv[0] == "report":
        return report(argv[1], argv[2], argv[3:])
    if len(argv) >= 2 and argv[0] == "check":
        return check([a for a in argv[1:] if a != "--quick"], "--quick" in argv[1:])
    raise InputError(__doc__.strip())


if __name__ == "__main__":
    run_main(main)
