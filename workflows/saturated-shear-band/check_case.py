#!/usr/bin/python3
"""Physics checks of the saturated shear-band case (README.md), on the outputs of its runs.

Usage: check_case.py --out OUT --runs psi15-k1e-16 ... psi15-dry psi0-dry [--quick]

Per run:
  - the run completed, and its energy balance holds (case 1's limit: |balance error| < 1 %);
  - saturated runs: the fluid is conserved, |fluid_mass_balance| of energy.csv at round-off
    (MAX_FLUID_BALANCE, relative to the pore volume);
  - the dry runs and the drained end (k = 1e-10 m^2) form two conjugate bands (case 1's check).
Per dilatancy (the dry run against the saturated ones):
  - the drained end (k = 1e-10) reproduces the dry load curve (DRAINED_TOLERANCE of the dry
    peak, the curves averaged over CURVE_WINDOW of travel, up to the dry peak's travel; after
    it the difference is printed: the bands' own drainage is slower, see the comment), its peak
    and its band angle;
  - the least permeable run (k = 1e-16, undrained over the loading):
    psi > 0: suction in the bands (mean band pore pressure below 0 and below the mean outside
    them), a peak load above the dry one by more than DRAINED_TOLERANCE, and a band later than
    the dry run's (by at least one snapshot of platen travel, or none by the end);
    psi = 0: no suction in the bands (mean band pore pressure >= 0), and the peak load not
    raised beyond DRAINED_TOLERANCE: the plastic flow does not change the volume, so nothing
    sucks the water in.
--quick (the test suite's reduced form: the platens 4x faster, k = 1e-16 and dry) checks what
those runs can show: everything above but the drained end, which needs its k = 1e-10 runs.
Prints one PASS/FAIL/SKIP line per check; exit 1 if any fails, 2 if the outputs are unusable.
"""
import math
import sys

import numpy as np

import saturated_measures as sm
from case_checks import run_case_checks  # ../tools, on the path saturated_measures sets

MAX_BALANCE_ERROR = sm.case1_check.MAX_BALANCE_ERROR  # case 1's energy criterion (1 %)
# fluid_mass_balance is the volume change of the pores less the inflow plus the outflow, summed
# in double precision over every point and step: its round-off grows at most like flow updates
# x eps of the volumes it adds, 57 760 steps x 2.2e-16 = 1.3e-11 of the pore volume (even
# counting each of the 31 stages of an RKL2 super step at k = 1e-10 as an update: 3.9e-10);
# the limit 1e-9 is above that worst case and still 3e3 below what one point losing a percent
# of its pore volume would book (3e-6 of the pore volume): a leak cannot hide in it.
MAX_FLUID_BALANCE = 1e-9
# The drained end against the dry run: at k = 1e-10 the specimen's consolidation time over
# half its height (drained top and bottom), H^2 / c_v with c_v = (k / mu_f) / (1/M + b^2 /
# (lambda + 2 mu)) = 5.4 m^2/s, is 1.9 ms, 1 % of the 0.18 s of loading, so the excess pore
# pressure is about 1 % of the stress change; the flow's super step moved the platen force by
# up to 3 % there (README.md, "Pore fluid"); the saturated run also has 1.27x the mass and half
# the time step (inertia and rate effects below 1 % at 0.05 m/s). Sum: 5 % of the dry peak.
# The same 5 % is the floor an undrained effect on the peak must clear to count as one.
DRAINED_TOLERANCE = 0.05
# That estimate holds while the specimen deforms as a whole, i.e. up to the peak. After it the
# shearing gathers in bands ~20 mm wide, whose dilation rate is about H / w ~ 10x the
# specimen's, and their water must come from the platens 100 mm away (the sides are
# impermeable): p ~ eps_v' mu_f L^2 / k ~ 1.3/s x 1e-3 Pa s x (0.1 m)^2 / 1e-10 m^2 ~ 0.1 MPa of
# suction even at k = 1e-10 with psi = 15 deg, enough to hold the softening up by several
# percent. So the curve is compared up to the dry peak's travel and the rest is printed.
# The load curves ring (the platens start at full speed): a P wave crosses the specimen's
# 200 mm in 0.2 ms (undrained, 1100 m/s) to 1 ms (drained, 207 m/s), so the ringing period is
# at most ~2 ms, 0.1 mm of travel, and differs between the two runs (the water stiffens the
# saturated one); both curves are averaged over CURVE_WINDOW of travel (>= 5 periods).
CURVE_WINDOW = 0.5e-3  # m of platen travel
# Band angles: the postprocessor's angle error is 1.5 deg per run on this lattice
# (case 1's check_case.py), so two runs with the same bands agree within 3 deg.
MAX_ANGLE_DIFFERENCE_DEG = sm.case1_check.MAX_RIDGE_DIFFERENCE_DEG
DRAINED_END = 1e-10  # m^2: the most permeable run of the sweep
UNDRAINED_END = 1e-16  # m^2: the least permeable


def averaged_curve(run):
    """(travel, load) of the top platen up to the platens' stop, the load averaged over
    CURVE_WINDOW of travel centred on each sample."""
    moving = run["curve"]["time_s"] <= run["platen_stop_s"] + 1e-12
    travel = np.abs(run["curve"]["top_uy_m"][moving])
    order = np.argsort(travel)
    travel, load = travel[order], np.abs(run["curve"]["top_Fy_N"][moving])[order]
    sums = np.concatenate([[0.0], np.cumsum(load)])
    low = np.searchsorted(travel, travel - 0.5 * CURVE_WINDOW)
    high = np.searchsorted(travel, travel + 0.5 * CURVE_WINDOW, side="right")
    return travel, (sums[high] - sums[low]) / (high - low)


def curve_difference(run, dry):
    """Largest (load(run) - load(dry)) / dry peak of the averaged curves, signed, and where
    [m], (before the dry peak's travel, after it)."""
    travel, dry_load = averaged_curve(dry)
    run_travel, run_load = averaged_curve(run)
    difference = (np.interp(travel, run_travel, run_load) - dry_load) / dry["summary"]["peak_load_N"]
    before = travel <= dry["summary"]["displacement_at_peak_m"]
    worst = lambda mask: (float(difference[mask][np.argmax(np.abs(difference[mask]))]),  # noqa: E731
                          float(travel[mask][np.argmax(np.abs(difference[mask]))])) if mask.any() else (0.0, None)
    return worst(before), worst(~before)


def snapshot_travel(run):
    """Platen travel [m] over one output interval of the run (the onset's resolution)."""
    interval = float(run["scene"]["output"]["interval"])
    top = next(bc for bc in run["scene"]["boundary_conditions"] if bc.get("name") == "top" and bc["type"] == "velocity")
    return interval * max(math.hypot(*[float(v) for v in velocity]) for _, velocity in top["history"])


def mm(length):
    return "none" if length is None else f"{1e3 * length:.2f} mm"


def mpa(pressure):
    return "n/a" if pressure is None else f"{pressure / 1e6:+.3f} MPa"


def measure_all(out, runs):
    """{name: measures}; the dry runs first, so that each saturated run without bands of its
    own gets its band pressure over the dry run's bands of its dilatancy."""
    parsed = {name: sm.parse_run_name(name) for name in runs}
    results = {}
    for name in sorted(runs, key=lambda n: parsed[n][1] is not None):
        psi, k, quick = parsed[name]
        dry = next((m for m in results.values() if m["dry"] and m["psi"] == psi and m["quick"] == quick), None)
        results[name] = sm.run_measures(out, name, reference_bands=dry and dry["bands"])
    return results


def per_run(m, report):
    name = m["name"]
    status = m["info"].get("status")
    report(status == "completed", f"{name}: run status '{status}' (expected completed)")
    report(m["worst_balance_error"] < MAX_BALANCE_ERROR,
           f"{name}: largest |energy balance error| {m['worst_balance_error']:.2g} (limit {MAX_BALANCE_ERROR:g})")
    if not m["dry"]:
        relative = m["worst_fluid_balance_m3"] / m["pore_volume_m3"]
        report(relative < MAX_FLUID_BALANCE,
               f"{name}: largest |fluid_mass_balance| {m['worst_fluid_balance_m3']:.2g} m^3 = {relative:.2g} of the "
               f"pore volume (limit {MAX_FLUID_BALANCE:g}: round-off)")
    if m["dry"] or m["permeability"] == DRAINED_END:
        bands = m["bands"]
        contrasts = m["contrasts"]
        conjugate = len(bands) == 2 and sorted(b.slope_sign for b in bands) == [-1, 1]
        ok = conjugate and all(c is not None and c >= sm.MIN_STRAIN_CONTRAST for c in contrasts)
        report(ok, f"{name}: two conjugate bands (arm/outside strain >= {sm.MIN_STRAIN_CONTRAST:g}): "
                   + (", ".join(f"{b.angle:.1f} deg, {1e3 * b.width:.1f} mm wide, contrast "
                                + ("n/a" if c is None else f"{c:.2f}")
                                for b, c in zip(bands, contrasts or [None] * len(bands))) or "no band"))


def per_dilatancy(psi, members, report, quick):
    dry = next((m for m in members if m["dry"]), None)
    by_k = {m["permeability"]: m for m in members if not m["dry"]}
    if dry is None:
        report(False, f"psi = {psi:g} deg: no dry run to compare with")
        return
    dry_peak = dry["summary"]["peak_load_N"]
    drained = by_k.get(DRAINED_END)
    if quick:
        report(None, f"psi = {psi:g} deg: the drained end (k = {DRAINED_END:g} m^2) is not in the quick form")
    elif drained is None:
        report(False, f"psi = {psi:g} deg: no run at k = {DRAINED_END:g} m^2 (the drained end)")
    else:
        (before, at_before), (after, at_after) = curve_difference(drained, dry)
        window = f"averaged over {1e3 * CURVE_WINDOW:g} mm of travel"
        report(abs(before) <= DRAINED_TOLERANCE,
               f"psi = {psi:g} deg: k = {DRAINED_END:g} m^2 follows the dry load curve up to the dry peak's "
               f"{mm(dry['summary']['displacement_at_peak_m'])}: largest difference {100 * before:+.2f} % of the dry "
               f"peak at {mm(at_before)} ({window}; limit {100 * DRAINED_TOLERANCE:g} %)")
        report(None, f"psi = {psi:g} deg: k = {DRAINED_END:g} m^2 after the dry peak, to the platens' stop: largest "
                     f"difference {100 * after:+.2f} % of the dry peak at {mm(at_after)} (the bands' suction: "
                     f"band pore pressure {mpa(drained['band_pressure_Pa'])} at the platens' stop)")
        peak = drained["summary"]["peak_load_N"]
        report(abs(peak / dry_peak - 1) <= DRAINED_TOLERANCE,
               f"psi = {psi:g} deg: k = {DRAINED_END:g} m^2 peak load {peak:.0f} N against dry {dry_peak:.0f} N "
               f"({100 * (peak / dry_peak - 1):+.2f} %, limit {100 * DRAINED_TOLERANCE:g} %)")
        a, b = drained["summary"].get("shear_band_angle_deg"), dry["summary"].get("shear_band_angle_deg")
        report(a is not None and b is not None and abs(a - b) <= MAX_ANGLE_DIFFERENCE_DEG,
               f"psi = {psi:g} deg: k = {DRAINED_END:g} m^2 band angle {a if a is None else f'{a:.1f}'} deg against dry "
               f"{b if b is None else f'{b:.1f}'} deg (within {MAX_ANGLE_DIFFERENCE_DEG:g})")
    if len(by_k) > 1:  # the sweep, printed (SKIP: measured, not asserted)
        ordered = [by_k[k] for k in sorted(by_k)]
        report(None, f"psi = {psi:g} deg: peak load against k: " + ", ".join(
            f"{m['permeability']:g}: {m['summary']['peak_load_N']:.0f} N" for m in ordered) + f"; dry {dry_peak:.0f} N")
        report(None, f"psi = {psi:g} deg: band onset against k: " + ", ".join(
            f"{m['permeability']:g}: {mm(m['onset_travel_m'])}" for m in ordered) + f"; dry {mm(dry['onset_travel_m'])}")
        report(None, f"psi = {psi:g} deg: band pore pressure against k: " + ", ".join(
            f"{m['permeability']:g}: {mpa(m['band_pressure_Pa'])}" for m in ordered))
    undrained = by_k.get(UNDRAINED_END)
    if undrained is None:
        report(False, f"psi = {psi:g} deg: no run at k = {UNDRAINED_END:g} m^2 (the undrained end)")
        return
    label = f"psi = {psi:g} deg, k = {UNDRAINED_END:g} m^2"
    band_p, outside_p = undrained["band_pressure_Pa"], undrained["outside_pressure_Pa"]
    where = {"own": "its bands", "reference": "the dry run's bands (it has none of its own)"}.get(
        undrained["pressure_bands"], "no bands")
    peak = undrained["summary"]["peak_load_N"]
    rise = peak / dry_peak - 1
    if psi > 0:
        report(band_p is not None and band_p < 0 and band_p < outside_p,
               f"{label}: suction in the bands: mean pore pressure over {where} {mpa(band_p)}, outside "
               f"{mpa(outside_p)} at the platens' stop (need < 0 and below the outside)")
        report(rise > DRAINED_TOLERANCE,
               f"{label}: the suction raises the peak load: {peak:.0f} N against dry {dry_peak:.0f} N "
               f"({100 * rise:+.1f} %, need > +{100 * DRAINED_TOLERANCE:g} %)")
        late, early = undrained["onset_travel_m"], dry["onset_travel_m"]
        step = snapshot_travel(undrained)
        delayed = early is not None and (late is None or late >= early + step - 1e-12)
        report(delayed, f"{label}: the band forms later than in the dry run: at {mm(late)} of travel "
                        f"(none: not by the end) against {mm(early)} (need one snapshot, {mm(step)}, later)")
    else:
        report(band_p is not None and band_p >= 0,
               f"{label}: no suction in the bands (no plastic dilation): mean pore pressure over {where} "
               f"{mpa(band_p)}, outside {mpa(outside_p)} at the platens' stop (need >= 0)")
        report(rise <= DRAINED_TOLERANCE,
               f"{label}: the peak load is not raised: {peak:.0f} N against dry {dry_peak:.0f} N "
               f"({100 * rise:+.1f} %, need <= +{100 * DRAINED_TOLERANCE:g} %)")


def check(out, runs, report, quick=False):
    results = measure_all(out, runs)
    for name in runs:
        per_run(results[name], report)
    for psi in sorted({m["psi"] for m in results.values()}, reverse=True):
        per_dilatancy(psi, [m for m in results.values() if m["psi"] == psi], report, quick)
    return results


def main():
    return run_case_checks(__doc__, check, "run names psi<deg>-k<m^2>|dry[-quick]")


if __name__ == "__main__":
    sys.exit(main())
