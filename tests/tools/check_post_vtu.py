#!/usr/bin/python3
# Reads every .vtu of a results.pvd with meshio and compares it with the values the run wrote
# (EXPECTED.json, dumped by the C++ test from the snapshot files through read_snapshot):
# reference positions as points, one vertex cell per point, every field (2-D vectors padded
# with z = 0), region/boundary_id/volume, and the derived invariants recomputed here with
# numpy from the stress and couple-stress tensors.
# Usage: check_post_vtu.py RESULTS.pvd EXPECTED.json     (exit 0 = all good)
import json
import os
import sys
import xml.etree.ElementTree as ET

import meshio
import numpy as np


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def main():
    pvd, expected_path = sys.argv[1], sys.argv[2]
    with open(expected_path) as f:
        expected = json.load(f)
    datasets = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
    frames = expected["frames"]
    if len(datasets) != len(frames):
        fail(f"{pvd} lists {len(datasets)} datasets, the run has {len(frames)} snapshots")
    dimension = expected["dimension"]
    reference = expected["reference"]
    positions = np.array(reference["position"]["data"]).reshape(-1, 3)
    n = positions.shape[0]
    for dataset, frame in zip(datasets, frames):
        time = float(dataset.get("timestep"))
        if time != frame["time"][0]:
            fail(f"{dataset.get('file')}: timestep {time} != snapshot time {frame['time'][0]}")
        path = os.path.join(os.path.dirname(pvd), dataset.get("file"))
        mesh = meshio.read(path)
        if not np.array_equal(mesh.points, positions):
            fail(f"{path}: points are not the reference positions")
        vertices = [block for block in mesh.cells if block.type == "vertex"]
        if sum(len(b.data) for b in vertices) != n or len(vertices) != len(mesh.cells):
            fail(f"{path}: expected {n} vertex cells, got {[(b.type, len(b.data)) for b in mesh.cells]}")
        connectivity = np.concatenate([b.data.reshape(-1) for b in vertices])
        if not np.array_equal(np.sort(connectivity), np.arange(n)):
            fail(f"{path}: vertex cells do not cover every point once")
        data = mesh.point_data
        names_expected = set(frame["fields"]) | {"volume", "region", "boundary_id"}
        for name, field in frame["fields"].items():
            if name not in data:
                fail(f"{path}: missing point array '{name}'")
            values = np.array(field["data"]).reshape(n, field["components"])
            got = np.asarray(data[name]).reshape(n, -1)
            if dimension == 2 and field["components"] == 2:
                if got.shape[1] != 3 or np.any(got[:, 2] != 0.0):
                    fail(f"{path}: 2-D vector '{name}' must be padded to 3 components with z = 0")
                got = got[:, :2]
            if got.shape != values.shape or not np.array_equal(got, values):
                fail(f"{path}: '{name}' differs from the snapshot (max |diff| "
                     f"{np.max(np.abs(got - values)) if got.shape == values.shape else 'shape ' + str(got.shape)})")
        for name in ("volume", "region", "boundary_id"):
            want = np.array(reference[name]["data"])
            if name not in data or not np.array_equal(np.asarray(data[name]).reshape(-1), want):
                fail(f"{path}: reference array '{name}' missing or different")
        if "region" in data and not np.issubdtype(np.asarray(data["region"]).dtype, np.integer):
            fail(f"{path}: 'region' should be an integer array (for thresholds)")
        # Derived invariants, recomputed independently. Relative tolerance 1e-12: the same
        # formula, only the floating-point evaluation order may differ.
        if "stress" in frame["fields"]:
            components = frame["fields"]["stress"]["components"]
            if components == 4 and dimension == 2:  # in-plane block, embedded with sigma_zz = 0
                plane = np.array(frame["fields"]["stress"]["data"]).reshape(n, 2, 2)
                sigma = np.zeros((n, 3, 3))
                sigma[:, :2, :2] = plane
            else:
                sigma = np.array(frame["fields"]["stress"]["data"]).reshape(n, 3, 3)
            sym = 0.5 * (sigma + np.transpose(sigma, (0, 2, 1)))
            p = np.trace(sigma, axis1=1, axis2=2) / 3.0
            dev = sym - p[:, None, None] * np.eye(3)
            q = np.sqrt(1.5 * np.sum(dev * dev, axis=(1, 2)))
            for name, want in (("von_mises_stress", q), ("mean_stress", p)):
                got = np.asarray(data.get(name, np.zeros(0))).reshape(-1)
                if got.shape != want.shape or not np.allclose(got, want, rtol=1e-12, atol=1e-12 * np.max(np.abs(want))):
                    fail(f"{path}: '{name}' is not the invariant of 'stress'")
            names_expected |= {"von_mises_stress", "mean_stress"}
        if "couple_stress" in frame["fields"]:
            m = np.array(frame["fields"]["couple_stress"]["data"]).reshape(n, -1)
            want = np.sqrt(np.sum(m * m, axis=1))
            got = np.asarray(data.get("couple_stress_magnitude", np.zeros(0))).reshape(-1)
            if got.shape != want.shape or not np.allclose(got, want, rtol=1e-12, atol=0):
                fail(f"{path}: 'couple_stress_magnitude' is not |couple_stress|")
            names_expected.add("couple_stress_magnitude")
        extra = set(data) - names_expected
        if extra:
            fail(f"{path}: arrays the run does not hold: {sorted(extra)}")
        if "displacement" not in data:
            fail(f"{path}: no 'displacement' for Warp By Vector")
    print(f"frames checked: {len(frames)}")


if __name__ == "__main__":
    main()
