#!/usr/bin/python3
"""Writes results.md and the throughput figure from the benchmark CSVs (nothing typed in).

Reads out/benchmarks.csv (run_mppm.py) and, when present, out/lammps.csv (run_lammps.py), and
writes results.md with: every run; the cost of each effect relative to the plain elastic
(non-polar) model; the inactive-effect runs against the run without the effect; mppm against
LAMMPS peri/lps and peri/pmb at equal process count; the two-thread efficiency; the
crack-branching base case's wall time; memory per bond. Each performance target is stated next to
its measured value with "met" or "NOT met". Exit codes: 0 written; 2 bad input.
"""

import argparse
import csv
import datetime
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools"))
from mppm_outputs import save_figure, write_text  # noqa: E402
from script_exit import InputError, run_main  # noqa: E402


def read_rows(path, required):
    try:
        with open(path, newline="") as stream:
            rows = list(csv.DictReader(stream))
    except FileNotFoundError:
        if required:
            raise InputError(f"{path}: not found (run make first)")
        return []
    for r in rows:
        for key in ("threads", "points", "bonds", "steps", "peak_memory_bytes"):
            r[key] = int(r[key])
        for key in ("wall_seconds", "bond_updates_per_second"):
            r[key] = float(r[key])
        r["run_seconds"] = float(r["run_seconds"]) if r.get("run_seconds") else None
        # The fastest of `repeats` runs is the row; the slowest shows the machine's drift.
        r["wall_seconds_max"] = float(r["wall_seconds_max"]) if r.get("wall_seconds_max") else r["wall_seconds"]
        r["repeats"] = int(r["repeats"]) if r.get("repeats") else 1
    return rows


def find(rows, case, effects, threads):
    for r in rows:
        if r["case"] == case and r["effects"] == effects and r["threads"] == threads:
            return r
    return None


def read_instructions(path):
    try:
        with open(path, newline="") as stream:
            rows = list(csv.DictReader(stream))
    except FileNotFoundError:
        raise InputError(f"{path}: not found (make instructions)")
    for r in rows:
        r["steps"], r["bonds"], r["instructions"] = int(r["steps"]), int(r["bonds"]), int(r["instructions"])
        r["per_update"] = r["instructions"] / (r["bonds"] * r["steps"])
    return rows


def instruction_section(rows):
    """The cost of each effect as callgrind instructions (not moved by the machine's load)."""
    by_name = {r["effects"]: r for r in rows}
    none, polar = by_name.get("none"), by_name.get("micropolar")
    steps = rows[0]["steps"] if rows else 0
    out = ["## The same costs as instructions (callgrind)\n",
           f"Instructions executed inside the time step (ExplicitDynamics::step) per bond update, 1 thread, {steps} "
           "steps of the plate before any bond breaks (count_instructions.py): the same for every run of the same "
           "binary, so these ratios do not move with the machine's load as the wall times above do. Counted on a "
           "build for x86-64-v3 (build-callgrind/): valgrind 3.19 cannot run the AVX-512 of the timed build.\n",
           "| effects | instructions per bond update | relative to none | relative to micropolar |",
           "|---|---|---|---|"]
    for r in rows:
        rel_none = f"{r['per_update'] / none['per_update']:.3f}" if none else ""
        rel_polar = f"{r['per_update'] / polar['per_update']:.3f}" if polar else ""
        out.append(f"| {r['effects']} | {r['per_update']:.1f} | {rel_none} | {rel_polar} |")
    out.append("")
    if polar:
        inactive = [r for r in rows if "(inactive)" in r["effects"]]
        if inactive:
            verdicts = ", ".join(f"{r['effects']} {r['per_update'] / polar['per_update']:.3f}x" for r in inactive)
            cheaper = all(r["per_update"] > polar["per_update"] for r in inactive)
            out.append(f"The run without the effect is the cheaper one in instructions: {verdicts} of `micropolar` "
                       f"({'yes for both' if cheaper else '**not for all**'}). An inactive damage effect still books "
                       "every bond's work each step (that is how it knows no bond reached w_cr); an inactive "
                       "viscoplastic effect evaluates the yield function once per point.\n")
    return out


# The two codes are compared only when measured back to back (the Makefile reruns LAMMPS whenever
# it reruns mppm); CSVs written further apart than one make of the benchmarks are said to be.
SIDE_BY_SIDE_SECONDS = 3 * 3600


def measurement_times(mppm_csv, lammps_csv):
    """When each CSV was written, and whether the LAMMPS comparison is side by side."""
    if not os.path.exists(lammps_csv):
        return "LAMMPS was not measured (no lammps.csv).\n"
    mppm_time, lammps_time = (datetime.datetime.fromtimestamp(os.path.getmtime(path), datetime.timezone.utc)
                              for path in (mppm_csv, lammps_csv))
    line = (f"mppm measured up to {mppm_time:%Y-%m-%d %H:%M} UTC, LAMMPS up to {lammps_time:%Y-%m-%d %H:%M} UTC")
    if abs((mppm_time - lammps_time).total_seconds()) > SIDE_BY_SIDE_SECONDS:
        return line + (": **not measured in the same run**, so the ratios against LAMMPS below may "
                       "mix two states of the machine (run `make` after removing out/).\n")
    return line + ", in the same run.\n"


def verdict(ok):
    return "met" if ok else "**NOT met**"


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mppm", required=True, help="benchmarks.csv of run_mppm.py")
    parser.add_argument("--lammps", required=True, help="lammps.csv of run_lammps.py (may be missing)")
    parser.add_argument("--results", required=True, help="results.md to write")
    parser.add_argument("--figure", required=True, help="PNG of the throughputs")
    parser.add_argument("--machine", default="", help="one line describing the machine")
    parser.add_argument("--instructions", help="instructions.csv of count_instructions.py (optional)")
    args = parser.parse_args(argv)
    mppm = read_rows(args.mppm, True)
    lammps = read_rows(args.lammps, False)
    plate = [r for r in mppm if r["case"] == "plate"]
    if not plate:
        raise InputError(f"{args.mppm}: no plate rows")
    threads = sorted({r["threads"] for r in plate})
    out = []
    out.append("# Benchmarks: results\n")
    out.append("Written by `make` (report_benchmarks.py) from `out/benchmarks.csv` and `out/lammps.csv`; "
               "nothing typed in. " + (args.machine + " " if args.machine else "") +
               "`wall_seconds` is the time loop only (LAMMPS: its `Loop time`), `run_seconds` the whole "
               "`mppm-solve` run; a bond update is one bond of one point in one step (bonds counted "
               "from both ends, as LAMMPS counts them).\n")
    out.append(measurement_times(args.mppm, args.lammps))

    out.append("## Every run\n")
    out.append("Each row is the fastest of `repeats` runs (the thread or rank counts of a case taking "
               "turns); `slowest loop s` is the slowest of them: this VM's speed drifts by 10-30 % over "
               "minutes, and the fastest run is the one least slowed by it.\n")
    out.append("| case | effects | threads | points | bonds | steps | loop s | slowest loop s | repeats | run s | bond updates/s | peak memory MB | bytes per bond |")
    out.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in mppm + lammps:
        run_s = f"{r['run_seconds']:.2f}" if r["run_seconds"] is not None else ""
        out.append(f"| {r['case']} | {r['effects']} | {r['threads']} | {r['points']} | {r['bonds']} | {r['steps']} | "
                   f"{r['wall_seconds']:.2f} | {r['wall_seconds_max']:.2f} | {r['repeats']} | {run_s} | "
                   f"{r['bond_updates_per_second']:.3g} | "
                   f"{r['peak_memory_bytes'] / 1e6:.1f} | {r['peak_memory_bytes'] / r['bonds']:.1f} |")
    out.append("")

    out.append("## Cost of each effect (plate, time loop relative to the non-polar elastic model)\n")
    header = "| effects | " + " | ".join(f"{t} thread{'s' if t > 1 else ''}" for t in threads) + " |"
    out.append(header)
    out.append("|---" * (len(threads) + 1) + "|")
    names = []
    for r in plate:
        if r["effects"] not in names:
            names.append(r["effects"])
    for name in names:
        cells = []
        for t in threads:
            base, this = find(plate, "plate", "none", t), find(plate, "plate", name, t)
            cells.append(f"{this['wall_seconds'] / base['wall_seconds']:.2f}" if base and this else "")
        out.append(f"| {name} | " + " | ".join(cells) + " |")
    out.append("")

    out.append("## An effect that is on but inactive\n")
    out.append("Damage with G_cr = 1e12 N/m and viscoplasticity with a cohesion of 1e15 Pa: run_mppm.py "
               "checked that `load.csv` and the last snapshot are byte-identical to the `micropolar` run "
               "(it stops with an error otherwise). The run without the effect is the cheaper one when "
               "the ratio below is above 1.\n")
    out.append("| effect on, inactive | threads | loop s | loop s without it | ratio |")
    out.append("|---|---|---|---|---|")
    for r in plate:
        if "(inactive)" in r["effects"]:
            without = find(plate, "plate", "micropolar", r["threads"])
            if without:
                out.append(f"| {r['effects']} | {r['threads']} | {r['wall_seconds']:.2f} | {without['wall_seconds']:.2f} | "
                           f"{r['wall_seconds'] / without['wall_seconds']:.2f} |")
    out.append("")

    if args.instructions:
        out += instruction_section(read_instructions(args.instructions))

    region = [r for r in plate if "(region)" in r["effects"]]
    if region:
        out.append("## An effect limited to a region\n")
        out.append("Damage only in the box [[45, 8], [101, 32]] mm around the crack path (`material.damage.region`; "
                   "a third of the plate) against damage everywhere. Outside the box bonds never break and book no work.\n")
        out.append("| run | threads | loop s | loop s, damage everywhere | ratio |")
        out.append("|---|---|---|---|---|")
        for r in region:
            everywhere = find(plate, "plate", "micropolar+damage", r["threads"])
            if everywhere:
                out.append(f"| {r['effects']} | {r['threads']} | {r['wall_seconds']:.2f} | {everywhere['wall_seconds']:.2f} | "
                           f"{r['wall_seconds'] / everywhere['wall_seconds']:.2f} |")
        out.append("")

    out.append("## Performance targets (measured in this run)\n")
    out.append("| target | measured | |")
    out.append("|---|---|---|")
    # (mppm effect set, LAMMPS case, target ratio of bond updates per second, what is compared)
    yardsticks = [("none", "plate-lammps-lps", 2.0, "non-polar elastic >= 2x LAMMPS peri/lps"),
                  ("micropolar+damage", "plate-lammps-pmb", 1.0, "micro-polar + damage faster than LAMMPS peri/pmb")]
    for t in threads:
        for effects, lammps_case, target, what in yardsticks:
            ours, theirs = find(plate, "plate", effects, t), next((x for x in lammps if x["case"] == lammps_case and x["threads"] == t), None)
            if ours and theirs:
                ratio = ours["bond_updates_per_second"] / theirs["bond_updates_per_second"]
                met = ratio >= target if target > 1 else ratio > target
                out.append(f"| {what}, {t} process{'es' if t > 1 else ''} | {ours['bond_updates_per_second']:.3g} vs "
                           f"{theirs['bond_updates_per_second']:.3g}: {ratio:.2f}x | {verdict(met)} |")
    crack = [r for r in mppm if r["case"] == "crack-branching-base"]
    for r in crack:
        out.append(f"| crack-branching base case ({r['steps']} steps, its own output) < 10 s, {r['threads']} threads | "
                   f"{r['run_seconds']:.2f} s (time loop {r['wall_seconds']:.2f} s) | {verdict(r['run_seconds'] < 10)} |")
    if 1 in threads and 2 in threads:
        for name in names:
            one, two = find(plate, "plate", name, 1), find(plate, "plate", name, 2)
            if one and two:
                efficiency = one["wall_seconds"] / (2 * two["wall_seconds"])
                out.append(f"| two-thread efficiency >= 90 %, {name} | {100 * efficiency:.0f} % | {verdict(efficiency >= 0.9)} |")
    block = [r for r in mppm if r["case"] == "block-3d"]
    for r in block:
        per_bond = r["peak_memory_bytes"] / r["bonds"]
        out.append(f"| memory per bond, full model, < 40 bytes (3-D block, {r['points']} points, peak RSS / bonds) | "
                   f"{per_bond:.1f} bytes | {verdict(per_bond < 40)} |")
    full2 = find(plate, "plate", "all", max(threads))
    if full2:
        out.append(f"| memory per bond, full model, plate (peak RSS / bonds; libraries included) | "
                   f"{full2['peak_memory_bytes'] / full2['bonds']:.1f} bytes | |")
    out.append("")
    if not lammps:
        out.append("LAMMPS rows missing (`make lammps` did not run): no ratios against LAMMPS.\n")

    # Figure: bond updates per second of each plate effect set and LAMMPS, per thread count.
    labels = names + [r["effects"] for r in lammps if r["threads"] == threads[0]]
    fig, ax = plt.subplots(figsize=(9, 4.5))
    width = 0.8 / len(threads)
    for k, t in enumerate(threads):
        values = []
        for label in labels:
            r = find(plate, "plate", label, t) or next((x for x in lammps if x["effects"] == label and x["threads"] == t), None)
            values.append(r["bond_updates_per_second"] if r else 0.0)
        ax.bar([i + k * width for i in range(len(labels))], values, width, label=f"{t} thread(s) / rank(s)")
    ax.set_xticks([i + 0.4 - width / 2 for i in range(len(labels))])
    ax.set_xticklabels([label.replace("+", "+\n").replace("(", "\n(") for label in labels], fontsize=7, rotation=30)
    ax.set_ylabel("bond updates per second")
    ax.set_title(f"crack-branching plate, {plate[0]['points']} points, {plate[0]['steps']} steps (time loop)")
    ax.legend()
    fig.tight_layout()
    save_figure(fig, args.figure, dpi=110)
    out.append(f"![bond updates per second]({os.path.relpath(args.figure, os.path.dirname(os.path.abspath(args.results)))})\n")

    write_text(args.results, "\n".join(out))
    print(f"wrote {args.results} and {args.figure}")
    return 0


if __name__ == "__main__":
    run_main(main, input_errors=(KeyError, ValueError))
