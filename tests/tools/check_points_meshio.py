#!/usr/bin/python3
"""Independent read-back of a POINTS.vtp written for tests/data/scenes/pre_branching_plate.yaml.

meshio (5.x) has no PolyData reader, but its VTK XML decoder (meshio.vtu: raw appended data,
zlib blocks, UInt64 headers) is independent of VTK; this script parses the XML with
ElementTree, decodes every array with meshio's decoder and checks arrays and values against
the scene: 200 x 80 body points on the 0.5 mm lattice, volume dx^2 t, the four boundaries with
their types, tags and normals, and the notch geometry. Exit 0 if all checks pass.
"""
import sys
import tempfile

import numpy as np
from meshio.vtu import _vtu


def decode(path):
    # meshio's raw-appended decoder looks blocks up by DataArray offset; VTK writes string
    # arrays as <Array type="String">. Present those as DataArray (same block layout) in a copy.
    with open(path, "rb") as f:
        raw = f.read()
    head_end = raw.find(b"<AppendedData")
    raw = raw[:head_end].replace(b'<Array type="String"', b'<DataArray type="String"') + raw[head_end:]
    with tempfile.NamedTemporaryFile(suffix=".vtp") as copy:
        copy.write(raw)
        copy.flush()
        root = _vtu._parse_raw_binary(copy.name)  # raw appended data -> base64 text
    assert root.tag == "VTKFile" and root.attrib["type"] == "PolyData", root.attrib
    reader = _vtu.VtuReader.__new__(_vtu.VtuReader)
    reader.compression = root.attrib.get("compressor")
    reader.header_type = root.attrib.get("header_type", "UInt32")
    reader.byte_order = root.attrib.get("byte_order")
    appended = root.find("AppendedData").text.strip()
    assert appended[0] == "_"
    reader.appended_data = appended[1:]
    piece = root.find("PolyData/Piece")
    arrays = {}
    for section in ("PointData", "Points", "FieldData"):
        node = piece.find(section) if section != "FieldData" else root.find("PolyData/FieldData")
        for da in node.findall("DataArray") if node is not None else []:
            name = da.attrib.get("Name", "Points")
            if da.attrib["type"] == "String":
                continue  # names/types: checked through the counts below
            arrays[(section, name)] = reader.read_data(da)
    return int(piece.attrib["NumberOfPoints"]), arrays


def main(path):
    n, a = decode(path)
    failures = []

    def check(condition, message):
        if not condition:
            failures.append(message)

    dx, t, delta = 0.5e-3, 1e-3, 4.05 * 0.5e-3
    points = a[("Points", "Points")].reshape(-1, 3)
    volume = a[("PointData", "volume")].ravel()
    region = a[("PointData", "region")].ravel()
    boundary_id = a[("PointData", "boundary_id")].ravel()
    normal = a[("PointData", "normal")].reshape(-1, 3)
    check(points.shape == (n, 3), f"points shape {points.shape}")
    for name, arr in (("volume", volume), ("region", region), ("boundary_id", boundary_id)):
        check(arr.shape == (n,), f"{name} has {arr.shape} values for {n} points")
    check(np.all(points[:, 2] == 0.0), "2-D points must have z = 0")
    check(np.allclose(volume, dx * dx * t, rtol=1e-14, atol=0), "volume != dx^2 t")
    body = region == 0
    check(body.sum() == 200 * 80, f"body points {body.sum()} (expected 200 x 80)")
    # Cell centres of the 0.5 mm lattice: (i + 1/2) dx.
    frac = points[:, :2] / dx - 0.5
    check(np.allclose(frac, np.round(frac), atol=1e-6), "points off the cell-centre lattice")
    bx, by = points[body, 0], points[body, 1]
    check(bx.min() > 0 and bx.max() < 0.1 and by.min() > 0 and by.max() < 0.04, "body point outside the plate")
    # Scene: 1 top traction, 2 bottom traction, 3 left velocity, 4 right displacement.
    check(set(np.unique(region)) == {0, 3, 4}, f"regions {sorted(set(np.unique(region)))}")
    check(np.all(points[region == 3, 0] < 0) and np.all(points[region == 4, 0] > 0.1), "layer on the wrong side")
    check(np.all(points[region == 3, 0] >= -delta) and np.all(points[region == 4, 0] <= 0.1 + delta), "layer deeper than the horizon")
    check(np.all(boundary_id[region > 0] == region[region > 0]), "layer boundary_id != region")
    top = body & (boundary_id == 1)
    bottom = body & (boundary_id == 2)
    check(top.sum() == 200 and bottom.sum() == 200, f"loaded rows {top.sum()} / {bottom.sum()} (expected 200)")
    check(np.allclose(points[top, 1], 0.04 - dx / 2) and np.allclose(points[bottom, 1], dx / 2), "loaded rows not the edge rows")
    check(np.all(normal[top] == [0, 1, 0]) and np.all(normal[bottom] == [0, -1, 0]), "outward normals")
    check(np.all(normal[boundary_id == 0] == 0), "normal set on an unloaded point")
    f = lambda name: a[("FieldData", name)].ravel()
    check(f("dimension")[0] == 2, "dimension")
    check(f("spacing")[0] == dx and abs(f("horizon")[0] - delta) < 1e-15 and f("thickness")[0] == t, "spacing/horizon/thickness")
    check(f("boundary_count")[0] == 4, "boundary_count")
    check(np.allclose(f("boundary_areas"), [0.1 * t, 0.1 * t, 0.04 * t, 0.04 * t]), f"areas {f('boundary_areas')}")
    check(list(f("boundary_point_counts")) == [200, 200, (region == 3).sum(), (region == 4).sum()], "point counts")
    crack = a[("FieldData", "precrack_vertices")].reshape(-1, 2, 3)
    check(len(crack) > 0 and np.allclose(crack[:, :, 1], 0.02) and crack[:, :, 0].min() == 0
          and abs(crack[:, :, 0].max() - 0.05) < 1e-15, "notch geometry")
    check(abs(np.sum(np.linalg.norm(crack[:, 1] - crack[:, 0], axis=1)) - 0.05) < 1e-12, "notch length")
    if failures:
        print(f"{path}: {len(failures)} check(s) failed:\n  " + "\n  ".join(failures))
        return 1
    print(f"{path}: {n} points, all checks passed (read with meshio's VTK XML decoder)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
