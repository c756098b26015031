"""Measures of one run of the saturated shear-band case, shared by check_case.py and report_case.py.

The band measures are case 1's (../shear-band: band_measures.py, shear_band_fields.py and the
run measures of its check_case.py, imported, not copied); this module adds what the pore
fluid brings:

- band onset: the first snapshot at which both bands of the last snapshot (the postprocessor's
  centre lines and widths) are bands by case 1's criterion, the mean plastic shear strain on
  each band's arms at least MIN_STRAIN_CONTRAST times the mean outside the bands, and stay so
  in every later snapshot; given as the platen travel at that snapshot (load_curve.csv), so
  its resolution is one output interval of platen travel;
- band pore pressure: the mean pore pressure of the interior points inside the bands (and of
  those outside) at the snapshot where the platens stop, the end of the shearing (in the
  hold after it the fluid relaxes toward the drained faces);
- fluid mass balance: the largest |fluid_mass_balance| of energy.csv [m^3], against the pore
  volume of the body;
- wall time: run_info.json, and the machine's load average over the run when the Makefile's
  timing files and the load samples (timing/loadavg.txt) cover it.
"""
import importlib.util
import os
import re
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SHEAR_BAND = os.path.join(HERE, "..", "shear-band")
sys.path.insert(0, SHEAR_BAND)
from band_measures import BandRegions  # noqa: E402
from shear_band_fields import Snapshot  # noqa: E402  (puts ../tools on the path)
from mppm_outputs import RunOutputError, frames, read_csv_columns, resolved_scene  # noqa: E402


def _case1_module(name):
    """A module of ../shear-band whose name this folder also uses (check_case, report_case)."""
    spec = importlib.util.spec_from_file_location(f"shear_band_{name}", os.path.join(SHEAR_BAND, f"{name}.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


case1_check = _case1_module("check_case")
MIN_STRAIN_CONTRAST = case1_check.MIN_STRAIN_CONTRAST  # case 1's criterion of a band


def parse_run_name(name):
    """'psi15-k1e-16', 'psi0-dry', 'psi15-k1e-16-quick' -> (dilatancy [deg], permeability [m^2]
    or None for a dry run, quick?): what the Makefile sets for that run."""
    m = re.fullmatch(r"psi([\d.]+)-(?:k([\d.]+e-?\d+)|(dry))(-quick)?", name)
    if not m:
        raise RunOutputError(f"run name '{name}': expected psi<deg>-k<m^2>[-quick] or psi<deg>-dry[-quick]")
    return float(m.group(1)), None if m.group(3) else float(m.group(2)), bool(m.group(4))


def platen_stop_time(scene):
    """When the top platen stops [s]: the last time of its history with a non-zero velocity."""
    top = next(bc for bc in scene["boundary_conditions"] if bc.get("name") == "top" and bc["type"] == "velocity")
    return max(float(t) for t, velocity in top["history"] if any(velocity))


def band_onset(post_dir, horizon, bands, curve):
    """(travel [m], time [s]) of the band onset (module docstring), or (None, None)."""
    if len(bands) != 2 or not all(b.width for b in bands):
        return None, None
    series = frames(post_dir)
    onset = None
    for index in range(len(series)):
        regions = BandRegions(Snapshot(post_dir, horizon, frame=index), bands)
        contrasts = [regions.strain_contrast(k) for k in range(2)]
        banded = all(c is not None and c >= MIN_STRAIN_CONTRAST for c in contrasts)
        if banded and onset is None:
            onset = index
        elif not banded:
            onset = None
    if onset is None:
        return None, None
    time = series[onset][0]
    return float(np.interp(time, curve["time_s"], np.abs(curve["top_uy_m"]))), time


def band_pressure(post_dir, horizon, bands, time):
    """(mean pore pressure inside the bands, outside them) [Pa] at the snapshot nearest TIME."""
    series = frames(post_dir)
    index = int(np.argmin([abs(t - time) for t, _ in series]))
    snapshot = Snapshot(post_dir, horizon, frame=index)
    if snapshot.pore_pressure is None or len(bands) == 0 or not all(b.width for b in bands):
        return None, None
    regions = BandRegions(snapshot, bands)
    pressure = snapshot.pore_pressure[snapshot.interior]
    return float(pressure[regions.inside].mean()), float(pressure[regions.outside].mean())


def load_average(out, name):
    """Mean 1-minute load average over the run's solve stage: the samples of timing/loadavg.txt
    ('EPOCH LOAD1 ...' lines, when a sampler wrote them) within the stage's start and end
    (timing/solve-NAME.txt), else the mean of the values at its start and end that the Makefile
    keeps (timing/solve-NAME.load); None without either."""
    timing = os.path.join(out, "timing")
    stage = os.path.join(timing, f"solve-{name}.txt")
    samples = os.path.join(timing, "loadavg.txt")
    if os.path.isfile(stage) and os.path.isfile(samples):
        with open(stage) as f:
            start, end = (float(v) for v in f.read().split()[1:3])
        with open(samples) as f:
            rows = [line.split() for line in f if line.strip()]
        loads = [float(r[1]) for r in rows if len(r) > 1 and start <= float(r[0]) <= end]
        if loads:
            return float(np.mean(loads))
    ends = os.path.join(timing, f"solve-{name}.load")
    if os.path.isfile(ends):
        with open(ends) as f:
            loads = [float(line.split()[0]) for line in f if line.strip()]
        return float(np.mean(loads)) if loads else None
    return None


def run_measures(out, name, reference_bands=None):
    """Case 1's run measures (../shear-band/check_case.py) and the pore fluid's (module docstring).
    A run without two bands of its own (an undrained run may not localize within the travel) has
    its band pressure measured over REFERENCE_BANDS (the dry run's of the same dilatancy: where
    the drained specimen shears), flagged by m["pressure_bands"] = "reference"."""
    folder = os.path.join(out, name)
    psi, permeability, quick = parse_run_name(name)
    m = case1_check.run_measures(folder)
    summary = m["summary"]
    resolved_psi = float(summary["material"]["viscoplasticity"]["dilatancy_angle"])
    if abs(resolved_psi - psi) > 1e-6:
        raise RunOutputError(f"{folder}: resolved dilatancy {resolved_psi:g} deg does not match the run name")
    fluid = summary["material"].get("pore_fluid") if "pore_fluid" in (summary.get("effects") or []) else None
    if (fluid is None) != (permeability is None):
        raise RunOutputError(f"{folder}: the run's effects {summary.get('effects')} do not match its name")
    if fluid is not None and abs(float(fluid["permeability"]) / permeability - 1) > 1e-9:
        raise RunOutputError(f"{folder}: resolved permeability {fluid['permeability']} does not match the run name")
    post = os.path.join(folder, "post")
    horizon = summary["horizon_m"]
    curve = read_csv_columns(os.path.join(post, "load_curve.csv"))
    scene = resolved_scene(os.path.join(folder, "run"))
    stop = platen_stop_time(scene)
    m.update(name=name, psi=psi, permeability=permeability, quick=quick, curve=curve, scene=scene,
             platen_stop_s=stop, dry=permeability is None)
    m["onset_travel_m"], m["onset_time_s"] = band_onset(post, horizon, m["bands"], curve)
    own = len(m["bands"]) == 2 and all(b.width for b in m["bands"])
    m["pressure_bands"] = "own" if own else ("reference" if reference_bands else None)
    pressure_bands = m["bands"] if own else (reference_bands or [])
    m["band_pressure_Pa"], m["outside_pressure_Pa"] = band_pressure(post, horizon, pressure_bands, stop)
    energy = read_csv_columns(os.path.join(folder, "run", "energy.csv"))
    if fluid is not None:
        if "fluid_mass_balance" not in energy:
            raise RunOutputError(f"{folder}/run/energy.csv: no column fluid_mass_balance")
        m["worst_fluid_balance_m3"] = float(np.max(np.abs(energy["fluid_mass_balance"])))
        last = Snapshot(post, horizon)
        body_volume = last.body.sum() * summary["spacing_m"] ** 2 * float(scene["thickness"])
        m["pore_volume_m3"] = float(body_volume * (1.0 - float(summary["material"]["solid_fraction"])))
    m["load_average"] = load_average(out, name)
    return m
