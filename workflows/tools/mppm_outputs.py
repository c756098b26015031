"""Reading the outputs of mppm runs and writing files atomically, for the workflow scripts.

A run directory (mppm-solve -o) holds run_info.json, scene.resolved.yaml (the scene with every
default filled in, SI units), load.csv, energy.csv and the snapshots; a postprocessing
directory (mppm-postprocess -o) holds summary.json and results.pvd, the ParaView series of the
snapshots; a points file (mppm-preprocess -o) is VTK XML PolyData. docs/stages.md describes
each file. Every reader raises RunOutputError naming the file it could not read.

Every file a script writes goes through atomic_open: a temporary in the same directory,
flushed and synced, then renamed over the target, so an interrupted script never leaves a
half-written results.md, figure or CSV behind.

Standard library only at import (numpy, yaml and matplotlib's figure are used only by the
functions that need them), so the benchmark runners stay standard-library scripts.
"""
import contextlib
import csv
import json
import os
import re
import shutil
import struct
import xml.etree.ElementTree as ElementTree
import zlib


class RunOutputError(Exception):
    """A run's outputs are missing or unreadable (the message names the file)."""


# Writing

@contextlib.contextmanager
def atomic_open(path, mode="w", **kwargs):
    """open() for writing PATH through a temporary beside it, renamed over PATH only when the
    block ends without an exception (after flush and fsync); on an exception the temporary is
    removed and PATH is left as it was."""
    directory = os.path.dirname(os.path.abspath(path))
    temporary = os.path.join(directory, f".{os.path.basename(path)}.{os.getpid()}.tmp")
    try:
        with open(temporary, mode, **kwargs) as stream:
            yield stream
            stream.flush()
            os.fsync(stream.fileno())
        os.replace(temporary, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(temporary)
        raise


def write_text(path, text):
    with atomic_open(path) as stream:
        stream.write(text)


def save_figure(figure, path, dpi):
    """A matplotlib figure as PNG at PATH (atomically), then closed."""
    import matplotlib.pyplot as plt
    with atomic_open(path, "wb") as stream:
        figure.savefig(stream, format="png", dpi=dpi)
    plt.close(figure)


def copy_file(source, target):
    with open(source, "rb") as original, atomic_open(target, "wb") as copy:
        shutil.copyfileobj(original, copy)


# Reading

def read_json(path):
    try:
        with open(path) as stream:
            return json.load(stream)
    except (OSError, json.JSONDecodeError) as error:
        raise RunOutputError(f"{path}: {error}") from error


def read_csv_rows(path):
    """The rows of a CSV file with a header row, as dictionaries of strings."""
    try:
        with open(path, newline="") as stream:
            return list(csv.DictReader(stream))
    except OSError as error:
        raise RunOutputError(f"{path}: {error}") from error


def read_csv_columns(path):
    """Columns of a CSV file with a header row, as float arrays keyed by name."""
    import numpy as np
    try:
        with open(path, newline="") as stream:
            rows = list(csv.reader(stream))
    except OSError as error:
        raise RunOutputError(f"{path}: {error}") from error
    if len(rows) < 2:
        raise RunOutputError(f"{path}: no data rows")
    header, data = rows[0], rows[1:]
    try:
        values = np.array([[float(v) for v in row] for row in data if row])
    except ValueError as error:
        raise RunOutputError(f"{path}: {error}") from error
    return {name: values[:, i] for i, name in enumerate(header)}


def run_info(run_dir):
    return read_json(os.path.join(run_dir, "run_info.json"))


def resolved_scene(run_dir):
    """scene.resolved.yaml of a run directory, as nested dictionaries (SI units)."""
    import yaml  # Debian python3-yaml

    class SceneLoader(yaml.SafeLoader):
        """YAML 1.1 reads 8e+06 (no dot) as a string; the resolved scene writes numbers so."""
    SceneLoader.add_implicit_resolver(
        "tag:yaml.org,2002:float", re.compile(r"^[-+]?[0-9]+(\.[0-9]*)?[eE][-+]?[0-9]+$"), list("-+0123456789"))
    path = os.path.join(run_dir, "scene.resolved.yaml")
    try:
        with open(path) as stream:
            return yaml.load(stream, Loader=SceneLoader)
    except (OSError, yaml.YAMLError) as error:
        raise RunOutputError(f"{path}: {error}") from error


def load_rows(run_dir):
    return read_csv_rows(os.path.join(run_dir, "load.csv"))


def energy_rows(run_dir):
    return read_csv_rows(os.path.join(run_dir, "energy.csv"))


def summary(post_dir):
    return read_json(os.path.join(post_dir, "summary.json"))


def frames(post_dir):
    """(time, path) of every snapshot of the postprocessed series (results.pvd), in time order."""
    pvd = os.path.join(post_dir, "results.pvd")
    try:
        datasets = ElementTree.parse(pvd).getroot().iter("DataSet")
        series = [(float(d.get("timestep")), os.path.join(post_dir, d.get("file"))) for d in datasets]
    except (OSError, ElementTree.ParseError) as error:
        raise RunOutputError(f"{pvd}: {error}") from error
    if not series:
        raise RunOutputError(f"{pvd}: no frames")
    return sorted(series)


# Scene values the scripts derive

def prescribed_displacement(scene, boundary, component):
    """Displacement [m] a velocity condition imposes on BOUNDARY along COMPONENT (0 = x) by the
    scene's end time: the integral of its piecewise-linear velocity history (held at its last
    value after the last entry), e.g. speed x hold time for a platen that moves, then stops."""
    condition = next((bc for bc in scene["boundary_conditions"] if bc.get("name") == boundary), None)
    if condition is None or condition.get("type") != "velocity":
        raise RunOutputError(f"resolved scene: no velocity condition named '{boundary}'")
    history = [(float(t), float(v[component])) for t, v in condition["history"]]
    end = float(scene["time"]["end"])
    history.append((max(end, history[-1][0]), history[-1][1]))
    travel = 0.0
    for (t0, v0), (t1, v1) in zip(history, history[1:]):
        if t1 > end:  # the run stops inside this segment
            v1, t1 = v0 + (v1 - v0) * (end - t0) / (t1 - t0), end
        if t1 > t0:
            travel += 0.5 * (v0 + v1) * (t1 - t0)
    return travel


def vtk_field_array(path, name):
    """The values (floats) of one FieldData array of a VTK XML file with raw appended data, as
    mppm-preprocess writes its points file (UInt64 headers, zlib-compressed or plain blocks)."""
    try:
        with open(path, "rb") as stream:
            raw = stream.read()
    except OSError as error:
        raise RunOutputError(f"{path}: {error}") from error
    start = raw.find(b"<AppendedData")
    data = raw.find(b"_", raw.find(b">", start)) + 1
    if start < 0 or data <= 0:
        raise RunOutputError(f"{path}: no raw appended data")
    root = ElementTree.fromstring(raw[:start].decode() + "</VTKFile>")
    if root.get("header_type", "UInt32") != "UInt64":
        raise RunOutputError(f"{path}: header type {root.get('header_type')} (expected UInt64)")
    array = next((a for a in root.iter("DataArray") if a.get("Name") == name), None)
    if array is None or array.get("type") != "Float64":
        raise RunOutputError(f"{path}: no Float64 array '{name}'")
    offset = data + int(array.get("offset"))
    if root.get("compressor"):
        blocks = struct.unpack_from("<3Q", raw, offset)[0]
        sizes = struct.unpack_from(f"<{blocks}Q", raw, offset + 24)
        position, payload = offset + 24 + 8 * blocks, b""
        for size in sizes:
            payload += zlib.decompress(raw[position:position + size])
            position += size
    else:
        size = struct.unpack_from("<Q", raw, offset)[0]
        payload = raw[offset + 8:offset + 8 + size]
    return list(struct.unpack(f"<{len(payload) // 8}d", payload))
