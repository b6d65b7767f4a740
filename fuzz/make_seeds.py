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
    seeds["texture_advection.json"] = dict(base, method={
        "name": "texture-advection", "vectors": "V", "slices": [[0, 0, 1, 0, 0, 1],
                                                              [0.5, 0, 0, 1, 0, 0]],
        "steps": 4, "frame": 2, "dt": 0.1, "unsteady": False, "start_time": 0,
        "advection": "backward", "reinject": 40, "resolution": 64, "sheet_opacity": 0.6})
    seeds["spot_noise.json"] = dict(base, method={
        "name": "spot-noise", "vectors": "V", "iso": 4.5, "scalar": "temp", "band": 0.05,
        "count": 500, "dt": 0.02, "steps": 3, "frame": 3, "lifetime": 60,
        "spot_opacity": 1.5, "seed": 7})
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


# Hand-parsed text formats and the surfaces: the same hexahedron and tetrahedron.
def tetgen_node(base=0, attributes=True):
    head = f"# seed\n{len(POINTS)} 3 {1 if attributes else 0} 1\n"
    rows = [f"{i + base} {p[0]} {p[1]} {p[2]}" + (f" {TEMP[i]}" if attributes else "") + " 0"
            for i, p in enumerate(POINTS)]
    return head + "\n".join(rows) + "\n"


def tetgen_ele(base=0):
    # The hexahedron as 5 tets, then the top tet (node ids of CELLS).
    tets = [(0, 1, 3, 4), (1, 2, 3, 6), (1, 4, 5, 6), (3, 4, 6, 7), (1, 3, 4, 6), (4, 5, 6, 8)]
    rows = [f"{c + base} " + " ".join(str(i + base) for i in t) + f" {c % 2}"
            for c, t in enumerate(tets)]
    return f"{len(tets)} 4 1\n" + "\n".join(rows) + "\n"


def cube_faces():
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    return quads


def tetgen_poly(base=0, with_points=True):
    pts = POINTS[:8]
    out = [f"{len(pts) if with_points else 0} 3 0 0"]
    if with_points:
        out += [f"{i + base} {p[0]} {p[1]} {p[2]}" for i, p in enumerate(pts)]
    out.append(f"{len(cube_faces())} 1")
    for q in cube_faces():
        out += ["1 0 1", "4 " + " ".join(str(i + base) for i in q)]
    out += ["1", f"1 0.5 0.5 0.5"]
    return "\n".join(out) + "\n"


def tetgen_seeds():
    # Byte 0 picks what is read (0 .node, 1 .ele, 2 .poly); a NUL separates the second file.
    node0, node1 = tetgen_node(0), tetgen_node(1, False)
    return {"node_ele.bin": b"\x00" + node0.encode() + b"\x00" + tetgen_ele(0).encode(),
            "node_only.bin": b"\x00" + node1.encode(),
            "ele_node.bin": b"\x01" + tetgen_ele(1).encode() + b"\x00" + node1.encode(),
            "poly.bin": b"\x02" + tetgen_poly().encode(),
            "poly1.bin": b"\x02" + tetgen_poly(1).encode(),
            "poly_node.bin": b"\x02" + tetgen_poly(0, False).encode() + b"\x00" +
                             tetgen_node(0, False).encode()}


def csv_seeds():
    rows = ["x,y,z,temp,\"p\""] + [f"{p[0]},{p[1]},{p[2]},{t},{-t}" for p, t in zip(POINTS, TEMP)]
    return {"points.csv": ("\n".join(rows) + "\n").encode(),
            "crlf.csv": ("\r\n".join(["X, Y, Z", "0, 0, 0", "1e0, +2, -3.5e-1", " 4 ,5,6"]) +
                         "\r\n").encode()}


def mfem_mesh():
    out = ["MFEM mesh v1.0", "", "# seed", "dimension", "3", "", "elements", "4",
           "1 5 0 1 2 3 4 5 6 7", "2 4 4 5 6 8", "3 6 0 1 2 4 5 6", "4 7 0 1 2 3 8",
           "", "boundary", "1", "1 3 0 1 2 3", "", "vertices", str(len(POINTS)), "3"]
    out += [" ".join(str(c) for c in p) for p in POINTS]
    return ("\n".join(out) + "\n\nmfem_mesh_end\n").encode()


def off_file(colored=False):
    out = ["COFF" if colored else "OFF", f"8 {len(cube_faces()) + 1} 0"]
    out += [" ".join(str(c) for c in p) + (" 1 0 0 1" if colored else "") for p in POINTS[:8]]
    out += ["4 " + " ".join(map(str, q)) for q in cube_faces()]
    out.append("3 0 1 2")
    return "\n".join(out) + "\n"


def stl_triangles():
    tris = []
    for a, b, c, d in cube_faces():
        tris += [(a, b, c), (a, c, d)]
    return [[POINTS[i] for i in t] for t in tris]


def stl_ascii():
    out = ["solid seed"]
    for tri in stl_triangles():
        out += ["  facet normal 0 0 0", "    outer loop"]
        out += [f"      vertex {p[0]} {p[1]} {p[2]}" for p in tri]
        out += ["    endloop", "  endfacet"]
    return "\n".join(out + ["endsolid seed"]) + "\n"


def stl_binary():
    tris = stl_triangles()
    out = b"binary seed".ljust(80, b" ") + struct.pack("<I", len(tris))
    for tri in tris:
        out += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *p) for p in tri)
        out += b"\x00\x00"
    return out


def ply(fmt="ascii"):
    pts, faces = POINTS[:8], cube_faces()
    head = (f"ply\nformat {fmt} 1.0\ncomment seed\nelement vertex {len(pts)}\n"
            "property float x\nproperty float y\nproperty float z\n"
            f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
    if fmt == "ascii":
        body = "".join(f"{p[0]} {p[1]} {p[2]}\n" for p in pts)
        body += "".join("4 " + " ".join(map(str, q)) + "\n" for q in faces)
        return (head + body).encode()
    e = "<" if fmt == "binary_little_endian" else ">"
    body = b"".join(struct.pack(f"{e}3f", *p) for p in pts)
    body += b"".join(struct.pack(f"{e}B4i", 4, *q) for q in faces)
    return head.encode() + body


def obj():
    out = ["# seed", "o cube"] + [f"v {p[0]} {p[1]} {p[2]}" for p in POINTS[:8]]
    out += ["vn 0 0 1", "vt 0 0"]
    out += ["f " + " ".join(f"{i + 1}/1/1" for i in q) for q in cube_faces()[:3]]
    out += ["f " + " ".join(str(i + 1) for i in q) for q in cube_faces()[3:]]
    return "\n".join(out) + "\n"


def surface_seeds():
    # Byte 0 picks the extension: 0 .off, 1 .stl, 2 .ply, 3 .obj.
    return {"cube.off": b"\x00" + off_file().encode(), "cube_color.off": b"\x00" +
            off_file(True).encode(), "ascii.stl": b"\x01" + stl_ascii().encode(),
            "binary.stl": b"\x01" + stl_binary(), "ascii.ply": b"\x02" + ply(),
            "le.ply": b"\x02" + ply("binary_little_endian"),
            "be.ply": b"\x02" + ply("binary_big_endian"), "cube.obj": b"\x03" + obj().encode()}


def netcdf_classic(dims, gatts, variables, version=1):
    """A netCDF classic file (CDF-1, or CDF-2 with 64-bit offsets): dims is [(name, length)]
    (length 0: the unlimited dimension, of one record), gatts and each variable's attributes
    [(name, type, values)], variables [(name, type, dim names, attributes, values)]; types as
    netCDF's: 2 char (values a str), 4 int, 5 float, 6 double."""
    size = {2: 1, 4: 4, 5: 4, 6: 8}
    fmt = {4: ">i", 5: ">f", 6: ">d"}

    def pad(b):
        return b + b"\0" * (-len(b) % 4)

    def name(n):
        return struct.pack(">i", len(n)) + pad(n.encode())

    def values(t, v):
        if t == 2:
            return struct.pack(">i", len(v)), pad(v.encode())
        return struct.pack(">i", len(v)), pad(b"".join(struct.pack(fmt[t], x) for x in v))

    def atts(lst):
        if not lst:
            return b"\0" * 8
        out = struct.pack(">ii", 0x0C, len(lst))
        for n, t, v in lst:
            count, data = values(t, v)
            out += name(n) + struct.pack(">i", t) + count + data
        return out

    dim_ids = {n: i for i, (n, _) in enumerate(dims)}
    lengths = dict(dims)
    records = any(length == 0 for _, length in dims)
    head = b"CDF" + bytes([version]) + struct.pack(">i", 1 if records else 0)
    head += struct.pack(">ii", 0x0A, len(dims)) + b"".join(
        name(n) + struct.pack(">i", length) for n, length in dims)
    head += atts(gatts)

    def var_entries(begins):
        out = struct.pack(">ii", 0x0B, len(variables))
        for (n, t, vdims, vatts, _), begin in zip(variables, begins):
            count = 1
            for d in vdims:
                count *= lengths[d] if lengths[d] > 0 else 1
            out += name(n) + struct.pack(">i", len(vdims))
            out += b"".join(struct.pack(">i", dim_ids[d]) for d in vdims)
            out += atts(vatts) + struct.pack(">ii", t, (count * size[t] + 3) // 4 * 4)
            out += struct.pack(">i" if version == 1 else ">q", begin)
        return out

    header_size = len(head) + len(var_entries([0] * len(variables)))
    data, begins = b"", []
    for n, t, vdims, _, v in variables:
        begins.append(header_size + len(data))
        if not any(lengths[d] == 0 for d in vdims):
            data += values(t, v)[1]
    # Record variables begin after the fixed-size data, one after another within the record.
    record = b""
    for i, (_, t, vdims, _, v) in enumerate(variables):
        if any(lengths[d] == 0 for d in vdims):
            begins[i] = header_size + len(data) + len(record)
            record += values(t, v)[1]
    return head + var_entries(begins) + data + record


def exodus_seeds():
    """Exodus II files as the Exodus library lays them out in netCDF (CDF-1 and CDF-2): the cube
    and tet of POINTS/CELLS as a HEX8 and a TETRA4 block with a nodal variable, a side set and a
    node set; and two cubes as polyhedra (NFACED over an NSIDED face block)."""
    def common(num_nodes, xyz):
        gatts = [("api_version", 5, [8.03]), ("version", 5, [8.03]),
                 ("floating_point_word_size", 4, [8]), ("file_size", 4, [1]),
                 ("maximum_name_length", 4, [32]), ("title", 2, "seed")]
        dims = [("len_name", 33), ("time_step", 0), ("num_dim", 3), ("num_nodes", num_nodes)]
        variables = [("time_whole", 6, ["time_step"], [], [0.0]),
                     ("coordx", 6, ["num_nodes"], [], [p[0] for p in xyz]),
                     ("coordy", 6, ["num_nodes"], [], [p[1] for p in xyz]),
                     ("coordz", 6, ["num_nodes"], [], [p[2] for p in xyz])]
        return gatts, dims, variables

    gatts, dims, variables = common(len(POINTS), POINTS)
    hexes = [c for t, c in CELLS if t == 12]
    tets = [c for t, c in CELLS if t == 10]
    dims += [("num_elem", 2), ("num_el_blk", 2), ("num_el_in_blk1", 1), ("num_nod_per_el1", 8),
             ("num_el_in_blk2", 1), ("num_nod_per_el2", 4), ("num_side_sets", 1),
             ("num_side_ss1", 1), ("num_node_sets", 1), ("num_nod_ns1", 2), ("num_nod_var", 1)]
    variables += [
        ("eb_status", 4, ["num_el_blk"], [], [1, 1]),
        ("eb_prop1", 4, ["num_el_blk"], [("name", 2, "ID")], [1, 2]),
        ("connect1", 4, ["num_el_in_blk1", "num_nod_per_el1"], [("elem_type", 2, "HEX8")],
         [i + 1 for c in hexes for i in c]),
        ("connect2", 4, ["num_el_in_blk2", "num_nod_per_el2"], [("elem_type", 2, "TETRA4")],
         [i + 1 for c in tets for i in c]),
        ("ss_status", 4, ["num_side_sets"], [], [1]),
        ("ss_prop1", 4, ["num_side_sets"], [("name", 2, "ID")], [20]),
        ("elem_ss1", 4, ["num_side_ss1"], [], [1]), ("side_ss1", 4, ["num_side_ss1"], [], [5]),
        ("ns_status", 4, ["num_node_sets"], [], [1]),
        ("ns_prop1", 4, ["num_node_sets"], [("name", 2, "ID")], [30]),
        ("node_ns1", 4, ["num_nod_ns1"], [], [1, 9]),
        ("name_nod_var", 2, ["num_nod_var", "len_name"], [], "temp".ljust(33, "\0")),
        ("vals_nod_var1", 6, ["time_step", "num_nodes"], [], TEMP)]
    seeds = {"hex_tet.exo": netcdf_classic(dims, gatts, variables),
             "hex_tet_cdf2.exo": netcdf_classic(dims, gatts, variables, version=2)}

    cube2 = [(2, 0, 0), (2, 1, 0), (2, 0, 1), (2, 1, 1)]
    gatts, dims, variables = common(12, POINTS[:8] + cube2)
    faces = [(1, 4, 3, 2), (2, 3, 7, 6), (5, 6, 7, 8), (1, 2, 6, 5), (3, 4, 8, 7), (1, 5, 8, 4),
             (2, 9, 10, 3), (9, 11, 12, 10), (6, 7, 12, 11), (2, 6, 11, 9), (3, 10, 12, 7)]
    dims += [("num_elem", 2), ("num_face", 11), ("num_el_blk", 1), ("num_fa_blk", 1),
             ("num_fa_in_blk1", 11), ("num_nod_per_fa1", 44), ("num_el_in_blk1", 2),
             ("num_fac_per_el1", 12)]
    variables += [
        ("eb_status", 4, ["num_el_blk"], [], [1]),
        ("eb_prop1", 4, ["num_el_blk"], [("name", 2, "ID")], [1]),
        ("fa_status", 4, ["num_fa_blk"], [], [1]),
        ("fa_prop1", 4, ["num_fa_blk"], [("name", 2, "ID")], [10]),
        ("fbconn1", 4, ["num_nod_per_fa1"], [("elem_type", 2, "nsided")],
         [i for f in faces for i in f]),
        ("fbepecnt1", 4, ["num_fa_in_blk1"],
         [("entity_type1", 2, "NODE"), ("entity_type2", 2, "FACE")], [4] * 11),
        ("facconn1", 4, ["num_fac_per_el1"], [("elem_type", 2, "nfaced")],
         [1, 2, 3, 4, 5, 6, 2, 7, 8, 9, 10, 11]),
        ("ebepecnt1", 4, ["num_el_in_blk1"],
         [("entity_type1", 2, "FACE"), ("entity_type2", 2, "ELEM")], [6, 6])]
    seeds["polyhedra.exo"] = netcdf_classic(dims, gatts, variables)
    return seeds


class Provider:
    """Bytes in the order FuzzedDataProvider consumes them (integers from the end of the
    input, most significant byte first); bytes() gives the input."""

    def __init__(self):
        self.stream = []

    def byte(self, v):
        self.stream.append(v & 0xFF)
        return self

    def coord(self, v):  # fuzz_double's grid values -4..4 (selector < 150)
        return self.byte(int(v) + 4)

    def id(self, v):  # fuzz_id: a valid id (selector < 240, then one byte when < 256 points)
        return self.byte(0).byte(v)

    def u64(self, v):
        for k in range(7, -1, -1):
            self.byte(v >> (8 * k))
        return self

    def bytes(self):
        return bytes(reversed(self.stream))


def pipeline_tail(p, scalars):
    p.u64(12345).byte(8).byte(1)  # camera seed, max_fallback_cells, pairwise order
    p.byte(2).coord(-1)  # 2 control points, the first at -1
    for k in range(2):  # colour (3 probabilities), opacity, the step to the next point
        p.u64(0x3F << 56).u64(0x7F << 56).u64(0xBF << 56).u64((0x40 << 56) * (k + 1)).coord(2)
    p.coord(1)  # unit distance
    for s in scalars:
        p.coord(s)
    return p.u64(1 << 62).u64(1 << 61).u64(1 << 60)  # background


def mesh_pipeline_seeds():
    # Byte 0 (consumed first): bit 0 create path (0 TetMesh::create, 1 tetrahedralize), bits
    # 1-2 sort method, bits 3-4 integrator, bit 5 orthographic, bit 6 camera inside.
    pts = [p for p in POINTS]
    tets = [(0, 1, 3, 4), (1, 2, 3, 6), (1, 4, 5, 6), (3, 4, 6, 7), (1, 3, 4, 6), (4, 5, 6, 8)]
    seeds = {}
    for mode in (0x00, 0x0A, 0x14, 0x26, 0x48, 0x32):
        p = Provider().byte(mode).byte(len(pts))
        for q in pts:
            for c in q:
                p.coord(c)
        p.byte(len(tets))
        for t in tets:
            for i in t:
                p.id(i)
        p.byte(0)  # default degenerate tolerance
        seeds[f"tets_{mode:02x}.bin"] = pipeline_tail(p, [i % 5 - 2 for i in range(len(pts))]).bytes()
    # Mixed cells through make_unstructured_mesh + tetrahedralize: the hexahedron and the tet,
    # a wedge and a pyramid on the same points; a second copy with explicit offsets.
    cells = [(0, [0, 1, 2, 3, 4, 5, 6, 7]), (5, [4, 5, 6, 8]), (2, [0, 1, 2, 4, 5, 6]),
             (3, [0, 1, 2, 3, 8])]  # index into fuzz_mesh's kTypes: 12, 10, 13, 14
    for mode, explicit in ((0x01, 0), (0x0F, 1), (0x53, 0)):
        p = Provider().byte(mode).byte(len(pts))
        for q in pts:
            for c in q:
                p.coord(c)
        p.byte(len(cells)).byte(explicit)
        for kind, ids in cells:
            p.byte([12, 10, 13, 14, 11, 24, 25, 26, 27, 15, 16, 5, 9, 42].index(
                {0: 12, 5: 10, 2: 13, 3: 14}[kind]))
            if explicit:
                p.byte(1)
            for i in ids:
                p.byte(1).id(i)
        p.byte(1).byte(0).byte(0)  # merge points, no tolerance, unsupported cells are errors
        seeds[f"mixed_{mode:02x}.bin"] = pipeline_tail(p, [i % 3 for i in range(len(pts))]).bytes()
    return seeds


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    for target, seeds in [("scene", scene_seeds()), ("colormap_preset", colormap_seeds()),
                          ("legacy_vtk", legacy_seeds()), ("vtu", vtu_seeds()),
                          ("tetgen", tetgen_seeds()), ("csv", csv_seeds()),
                          ("mfem", {"mixed.mesh": mfem_mesh()}), ("surface", surface_seeds()),
                          ("exodus", exodus_seeds()),
                          ("mesh_pipeline", mesh_pipeline_seeds())]:
        os.makedirs(os.path.join(out, target), exist_ok=True)
        for name, data in seeds.items():
            with open(os.path.join(out, target, name), "wb") as f:
                f.write(data)


if __name__ == "__main__":
    main()
