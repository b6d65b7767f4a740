#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora: small valid inputs of each format, made here.

usage: make_seeds.py OUT_DIR   (writes OUT_DIR/<target>/<name> for each target in fuzz/)
"""
import json
import os
import struct
import sys

# A unit cube as a hexahedron, with a tetrahedron on its top: 9 points, 2 cells.
POINTS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1),
          (0.5, 0.5, 2)]
CELLS = [(12, [0, 1, 2, 3, 4, 5, 6, 7]), (10, [4, 5, 6, 8])]
TEMP = [1.5 * i for i in range(len(POINTS))]


def scene_seeds():
    tf = {"color": [[0, 0, 0, 1], [8, 1, 0, 0]], "opacity": [[0, 0], [8, 0.5]],
          "unit_distance": 0.5}
    camera = {"position": [3, 2, 4], "focal_point": [0.5, 0.5, 1], "view_up": [0, 0, 1]}
    image = {"width": 64, "height": 48}
    base = {"mesh": "m.vtu", "scalar": "temp", "transfer_function": tf, "camera": camera,
            "image": image}
    seeds = {"minimal.json": base}
    full = dict(base, component=0, time_step=0,
                camera=dict(camera, view_angle=40, parallel=True, parallel_scale=2),
                image=dict(image, background=[0.1, 0.2, 0.3]),
                method={"name": "pbvr-image", "repetitions": 4, "seed": 2, "depth": "entry",
                        "stratified": False, "control_variate": True})
    seeds["full.json"] = full
    seeds["volumes.json"] = {
        "volumes": [{"mesh": "a.vtu", "scalar": "s", "transfer_function": tf},
                    {"mesh": "b.vtu", "scalar": "t", "component": "magnitude",
                     "transfer_function": tf}],
        "camera": camera, "image": image,
        "method": {"name": "pbvr-object", "subpixel_level": 2, "sampling": "metropolis"}}
    seeds["opaque.json"] = dict(base, opaque=[{"file": "body.stl", "color": [0.8, 0.8, 0.8]},
                                              {"side_set": "wall"}, {"boundary": True}])
    seeds["flow_volume.json"] = dict(base, flow_volume={
        "vectors": "V", "seed_center": [2, 0, 8], "seed_size": [2, 2], "seed_resolution": 8,
        "seed_normal": [0, 0, -1], "steps": 6, "dt": 0.02, "compressible": False,
        "split_threshold": 2.0, "unsteady": False, "start_time": 0.0,
        "color": [0.85, 0.9, 1.0], "opacity": 0.3, "unit_distance": 0.5, "context": True})
    seeds["splat.json"] = dict(base, method={"name": "splat", "kernel": "gaussian",
                                             "spacing": 0.5, "compositing": "per-splat",
                                             "vectors": "V", "cycle": 4, "frame": 1})
    return {name: json.dumps(s, indent=1).encode() for name, s in seeds.items()}


def colormap_seeds():
    cool_warm = {"Name": "Cool to Warm", "ColorSpace": "Diverging",
                 "RGBPoints": [0, 0.23, 0.299, 0.754, 0.5, 0.865, 0.865, 0.865,
                               1, 0.706, 0.016, 0.15],
                 "NanColor": [1, 1, 0]}
    with_opacity = {"Name": "ramp", "ColorSpace": "Lab", "RGBPoints": [-1, 0, 0, 0, 2, 1, 1, 1],
                    "Points": [-1, 0, 0.5, 0, 2, 0.8, 0.5, 0]}
    hsv = {"Name": "hsv", "ColorSpace": "HSV", "RGBPoints": [0, 1, 0, 0, 1, 0, 0, 1]}
    return {"cool_warm.json": json.dumps([cool_warm]).encode(),
            "object.json": json.dumps(with_opacity).encode(),
            "several.json": json.dumps([hsv, cool_warm, with_opacity], indent=2).encode(),
            "rgb_gray.json": json.dumps([{"Name": "g", "ColorSpace": "RGB",
                                          "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1]}]).encode()}


def legacy_ascii(version="4.2", offsets=False):
    out = [f"# vtk DataFile Version {version}", "seed", "ASCII", "DATASET UNSTRUCTURED_GRID",
           f"POINTS {len(POINTS)} float"]
    out += [" ".join(str(c) for c in p) for p in POINTS]
    if offsets:
        conn = [i for _, ids in CELLS for i in ids]
        offs = [0]
        for _, ids in CELLS:
            offs.append(offs[-1] + len(ids))
        out += [f"CELLS {len(offs)} {len(conn)}", "OFFSETS vtktypeint64",
                " ".join(map(str, offs)), "CONNECTIVITY vtktypeint64", " ".join(map(str, conn))]
    else:
        size = sum(len(ids) + 1 for _, ids in CELLS)
        out.append(f"CELLS {len(CELLS)} {size}")
        out += [" ".join(map(str, [len(ids)] + ids)) for _, ids in CELLS]
    out.append(f"CELL_TYPES {len(CELLS)}")
    out += [str(t) for t, _ in CELLS]
    out += [f"POINT_DATA {len(POINTS)}", "SCALARS temp float 1", "LOOKUP_TABLE default"]
    out += [str(v) for v in TEMP]
    out += ["VECTORS V double"] + [f"{p[1]} {-p[0]} 1" for p in POINTS]
    out += [f"CELL_DATA {len(CELLS)}", "SCALARS id int 1", "LOOKUP_TABLE default", "10 20"]
    return ("\n".join(out) + "\n").encode()


def legacy_binary(version="4.2", offsets=False):
    out = f"# vtk DataFile Version {version}\nseed\nBINARY\nDATASET UNSTRUCTURED_GRID\n".encode()
    out += f"POINTS {len(POINTS)} float\n".encode()
    out += b"".join(struct.pack(">3f", *p) for p in POINTS) + b"\n"
    if offsets:
        conn = [i for _, ids in CELLS for i in ids]
        offs = [0]
        for _, ids in CELLS:
            offs.append(offs[-1] + len(ids))
        out += f"CELLS {len(offs)} {len(conn)}\nOFFSETS vtktypeint64\n".encode()
        out += struct.pack(f">{len(offs)}q", *offs) + b"\nCONNECTIVITY vtktypeint64\n"
        out += struct.pack(f">{len(conn)}q", *conn) + b"\n"
    else:
        size = sum(len(ids) + 1 for _, ids in CELLS)
        out += f"CELLS {len(CELLS)} {size}\n".encode()
        for _, ids in CELLS:
            out += struct.pack(f">{len(ids) + 1}i", len(ids), *ids)
        out += b"\n"
    out += f"CELL_TYPES {len(CELLS)}\n".encode()
    out += struct.pack(f">{len(CELLS)}i", *[t for t, _ in CELLS]) + b"\n"
    out += f"POINT_DATA {len(POINTS)}\nSCALARS temp float 1\nLOOKUP_TABLE default\n".encode()
    out += struct.pack(f">{len(TEMP)}f", *TEMP) + b"\n"
    return out


def legacy_structured():
    return (b"# vtk DataFile Version 3.0\nseed\nASCII\nDATASET STRUCTURED_POINTS\n"
            b"DIMENSIONS 3 2 2\nORIGIN 1 2 3\nSPACING 0.5 1 2\nPOINT_DATA 12\n"
            b"SCALARS temp float\nLOOKUP_TABLE default\n0 1 2 3 4 5 6 7 8 9 10 11\n"
            b"CELL_DATA 2\nSCALARS c int 1\nLOOKUP_TABLE default\n10 20\n")


def legacy_point_cloud():
    return (b"# vtk DataFile Version 4.2\nseed\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n"
            b"0 0 0 1 0 0 0 1 0 0 0 1\nVERTICES 4 8\n1 0\n1 1\n1 2\n1 3\n"
            b"POINT_DATA 4\nSCALARS s double 1\nLOOKUP_TABLE default\n1 2 3 4\n")


def legacy_seeds():
    return {"ascii42.vtk": legacy_ascii(), "ascii51.vtk": legacy_ascii("5.1", True),
            "ascii30.vtk": legacy_ascii("3.0"), "binary42.vtk": legacy_binary(),
            "binary51.vtk": legacy_binary("5.1", True), "structured.vtk": legacy_structured(),
            "point_cloud.vtk": legacy_point_cloud()}


def vtu(fmt="ascii", header="UInt32"):
    conn = [i for _, ids in CELLS for i in ids]
    offs = []
    for _, ids in CELLS:
        offs.append((offs[-1] if offs else 0) + len(ids))
    arrays = [("Float32", "Points", 3, [c for p in POINTS for c in p], "pts"),
              ("Int64", "connectivity", 1, conn, "cell"), ("Int64", "offsets", 1, offs, "cell"),
              ("UInt8", "types", 1, [t for t, _ in CELLS], "cell"),
              ("Float64", "temp", 1, TEMP, "pd"), ("Int32", "id", 1, [10, 20], "cd")]
    codes = {"Float32": "f", "Float64": "d", "Int64": "q", "Int32": "i", "UInt8": "B"}
    hfmt = "<I" if header == "UInt32" else "<Q"
    appended = b""

    def data_array(type_, name, ncomp, values):
        nonlocal appended
        attrs = f'type="{type_}" Name="{name}" NumberOfComponents="{ncomp}"'
        if fmt == "ascii":
            return f'<DataArray {attrs} format="ascii">{" ".join(map(str, values))}</DataArray>'
        raw = struct.pack(f"<{len(values)}{codes[type_]}", *values)
        offset = len(appended)
        appended += struct.pack(hfmt, len(raw)) + raw
        return f'<DataArray {attrs} format="appended" offset="{offset}"/>'

    def section(kind):
        return "".join(data_array(t, n, c, v) for t, n, c, v, k in arrays if k == kind)

    xml = (f'<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" '
           f'byte_order="LittleEndian" header_type="{header}">\n<UnstructuredGrid>\n'
           f'<Piece NumberOfPoints="{len(POINTS)}" NumberOfCells="{len(CELLS)}">\n'
           f'<Points>{section("pts")}</Points>\n<Cells>{section("cell")}</Cells>\n'
           f'<PointData Scalars="temp">{section("pd")}</PointData>\n'
           f'<CellData>{section("cd")}</CellData>\n</Piece>\n</UnstructuredGrid>\n')
    if fmt == "ascii":
        return (xml + "</VTKFile>\n").encode()
    return (xml + '<AppendedData encoding="raw">\n_').encode() + appended + \
        b"\n</AppendedData>\n</VTKFile>\n"


def vtu_seeds():
    return {"ascii.vtu": vtu(), "raw32.vtu": vtu("raw"), "raw64.vtu": vtu("raw", "UInt64")}


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    for target, seeds in [("scene", scene_seeds()), ("colormap_preset", colormap_seeds()),
                          ("legacy_vtk", legacy_seeds()), ("vtu", vtu_seeds())]:
        os.makedirs(os.path.join(out, target), exist_ok=True)
        for name, data in seeds.items():
            with open(os.path.join(out, target, name), "wb") as f:
                f.write(data)


if __name__ == "__main__":
    main()
