"""Meshes in and out: numpy without a copy, read() views, meshio and PyVista-shaped input."""

import types

import meshio
import numpy as np
import pytest

import tetrender
from conftest import hex_ring


def data_pointer(array: np.ndarray) -> int:
    return array.__array_interface__["data"][0]


def test_numpy_arrays_are_kept_without_a_copy_when_the_layout_allows(ring):
    temperature32 = ring["point_data"]["temperature"].astype(np.float32)
    mesh = tetrender.Mesh(ring["points"], ring["connectivity"], ring["offsets"], ring["types"],
                          {"temperature": temperature32, "velocity": ring["point_data"]["velocity"]},
                          ring["cell_data"])
    assert data_pointer(mesh.points) == data_pointer(ring["points"])
    assert data_pointer(mesh.connectivity) == data_pointer(ring["connectivity"])
    assert data_pointer(mesh.offsets) == data_pointer(ring["offsets"])
    assert data_pointer(mesh.types) == data_pointer(ring["types"])
    assert data_pointer(mesh.point_data["temperature"]) == data_pointer(temperature32)
    assert data_pointer(mesh.point_data["velocity"]) == data_pointer(ring["point_data"]["velocity"])
    assert data_pointer(mesh.cell_data["material"]) == data_pointer(ring["cell_data"]["material"])


def test_other_layouts_are_converted_once(ring):
    points32 = ring["points"].astype(np.float32)
    strided = np.asfortranarray(ring["points"])
    conn32 = ring["connectivity"].astype(np.int32)
    mesh = tetrender.Mesh(points32, conn32, ring["offsets"], ring["types"])
    assert mesh.points.dtype == np.float64 and data_pointer(mesh.points) != data_pointer(points32)
    assert mesh.connectivity.dtype == np.int64
    assert data_pointer(tetrender.Mesh(strided).points) != data_pointer(strided)
    np.testing.assert_array_equal(tetrender.Mesh(strided).points, ring["points"])


def test_read_gives_read_only_views_of_the_library_mesh(ring, output_dir):
    path = output_dir / "ring.vtu"
    meshio.write(path, meshio.Mesh(ring["points"], [("hexahedron", ring["hexahedra"])],
                                   point_data=ring["point_data"], cell_data={"material": [ring["cell_data"]["material"]]}))
    mesh = tetrender.read(path)
    np.testing.assert_array_equal(mesh.points, ring["points"])
    np.testing.assert_array_equal(mesh.connectivity, ring["connectivity"])
    np.testing.assert_array_equal(mesh.offsets, ring["offsets"])
    np.testing.assert_array_equal(mesh.types, ring["types"])
    np.testing.assert_array_equal(mesh.point_data["temperature"], ring["point_data"]["temperature"])
    np.testing.assert_array_equal(mesh.point_data["velocity"], ring["point_data"]["velocity"])
    np.testing.assert_array_equal(mesh.cell_data["material"], ring["cell_data"]["material"])
    # The same memory each time it is asked for, not a copy; and it cannot be written.
    assert data_pointer(mesh._handle.points) == data_pointer(mesh.points)
    assert not mesh.points.flags.writeable
    with pytest.raises(ValueError):
        mesh.points[0, 0] = 1.0


def test_meshio_round_trip(ring, output_dir):
    source = meshio.Mesh(ring["points"], [("hexahedron", ring["hexahedra"])],
                         point_data=ring["point_data"], cell_data={"material": [ring["cell_data"]["material"]]})
    mesh = tetrender.Mesh.from_meshio(source)
    np.testing.assert_array_equal(mesh.connectivity, ring["connectivity"])
    np.testing.assert_array_equal(mesh.types, ring["types"])
    back = mesh.to_meshio()
    assert [b.type for b in back.cells] == ["hexahedron"]
    np.testing.assert_array_equal(back.cells[0].data, ring["hexahedra"])
    np.testing.assert_array_equal(back.cell_data["material"][0], ring["cell_data"]["material"])
    # Through a file: meshio writes, the library reads, the arrays are the same.
    path = output_dir / "round_trip.vtu"
    back.write(path)
    read = tetrender.read(path)
    np.testing.assert_array_equal(read.points, ring["points"])
    np.testing.assert_array_equal(read.connectivity, ring["connectivity"])
    np.testing.assert_array_equal(read.point_data["temperature"], ring["point_data"]["temperature"])
    # And back to meshio from the library's mesh.
    again = read.to_meshio()
    np.testing.assert_array_equal(again.cells[0].data, ring["hexahedra"])


def test_meshio_surface_blocks_are_dropped_by_default(ring):
    triangles = np.array([[0, 1, 2]], dtype=np.int64)
    source = meshio.Mesh(ring["points"], [("triangle", triangles), ("hexahedron", ring["hexahedra"])],
                         cell_data={"id": [np.array([7.0]), np.arange(len(ring["hexahedra"]), dtype=float)]})
    mesh = tetrender.Mesh.from_meshio(source)
    assert mesh.num_cells == len(ring["hexahedra"])
    np.testing.assert_array_equal(mesh.cell_data["id"], np.arange(len(ring["hexahedra"])))
    with pytest.raises(tetrender.Error, match="cell 0"):
        tetrender.tetrahedralize(tetrender.Mesh.from_meshio(source, volume_only=False))


def pyvista_like(ring, with_legacy_cells: bool):
    """An object with the attributes of a PyVista UnstructuredGrid, PyVista not imported."""
    n = len(ring["hexahedra"])
    grid = types.SimpleNamespace(points=ring["points"].astype(np.float32),
                                 celltypes=ring["types"], point_data=ring["point_data"],
                                 cell_data=ring["cell_data"])
    if with_legacy_cells:
        grid.cells = np.hstack([np.full((n, 1), 8), ring["hexahedra"]]).ravel()
    else:
        grid.cells = None
        grid.cell_connectivity = ring["connectivity"]
        grid.offset = ring["offsets"]
    return grid


@pytest.mark.parametrize("legacy", [True, False])
def test_pyvista_shaped_grid_gives_the_same_tets(ring, legacy):
    reference = tetrender.tetrahedralize(tetrender.Mesh(ring["points"].astype(np.float32).astype(np.float64),
                                                        ring["connectivity"], ring["offsets"], ring["types"],
                                                        ring["point_data"]))
    tets = tetrender.tetrahedralize(pyvista_like(ring, legacy))
    assert tets.num_cells == reference.num_cells > 0
    np.testing.assert_array_equal(tets.connectivity, reference.connectivity)
    np.testing.assert_array_equal(tets.points, reference.points)
    np.testing.assert_array_equal(tets.point_data["temperature"], reference.point_data["temperature"])


def test_tetrahedralize_splits_every_hexahedron_into_tets_of_its_volume(ring):
    tets = tetrender.tetrahedralize(tetrender.Mesh(ring["points"], ring["connectivity"], ring["offsets"],
                                                   ring["types"], ring["point_data"], ring["cell_data"]))
    assert set(tets.types) == {10}
    p = tets.points[tets.connectivity.reshape(-1, 4)]
    volume = np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0])) / 6
    assert (volume > 0).all()  # positively oriented
    # 32 unit hexahedra of side 1/6: the ring's volume (the split adds and loses nothing).
    assert abs(volume.sum() - len(ring["hexahedra"]) / 6**3) < 1e-12
    assert tets.report["tets"] == tets.num_cells


def test_bad_input_raises_with_the_library_message(ring):
    points = ring["points"].copy()
    points[5, 1] = np.nan
    with pytest.raises(tetrender.Error, match=r"point 5 has a non-finite coordinate"):
        tetrender.tetrahedralize(tetrender.Mesh(points, ring["connectivity"], ring["offsets"], ring["types"]))
    connectivity = ring["connectivity"].copy()
    connectivity[3] = 999
    with pytest.raises(tetrender.Error, match=r"cell 0: error: node 999 out of range \(147 points\)"):
        tetrender.tetrahedralize(tetrender.Mesh(ring["points"], connectivity, ring["offsets"], ring["types"]))
    with pytest.raises(tetrender.Error, match=r"points: expected an \(n, 3\) array, got shape \(147, 2\)"):
        tetrender.tetrahedralize(tetrender.Mesh(ring["points"][:, :2], ring["connectivity"], ring["offsets"], ring["types"]))
    with pytest.raises(tetrender.Error, match=r"point_data\['t'\]: 3 tuples for 147 points"):
        tetrender.tetrahedralize(tetrender.Mesh(ring["points"], ring["connectivity"], ring["offsets"],
                                                ring["types"], {"t": np.zeros(3)}))
    with pytest.raises(tetrender.Error, match=r"no_such\.vtu"):
        tetrender.read("no_such.vtu")
    with pytest.raises(tetrender.Error, match="expected a tetrender.Mesh"):
        tetrender.tetrahedralize(42)


def test_meshio_wedges_keep_vtk_node_order_both_ways(output_dir):
    # One VTK wedge (positive volume in VTK's order: the first triangle's normal points away
    # from the second triangle); meshio stores it in Gmsh's order (nodes 1-2, 4-5 swapped).
    points = np.array([[0, 0, 0], [0, 1, 0], [1, 0, 0], [0, 0, 1], [0, 1, 1], [1, 0, 1]], dtype=float)
    wedge = tetrender.Mesh(points, np.arange(6), None, [13], {"s": points[:, 2]})
    assert tetrender.tetrahedralize(wedge).report["inverted_cells"] == 0
    path = output_dir / "wedge.vtu"
    wedge.to_meshio().write(path)
    np.testing.assert_array_equal(tetrender.read(path).connectivity, np.arange(6))
    back = tetrender.Mesh.from_meshio(meshio.read(path))
    np.testing.assert_array_equal(back.connectivity, np.arange(6))


def test_a_field_added_to_a_read_mesh_is_handed_over(ring, output_dir):
    path = output_dir / "ring.vtu"
    meshio.write(path, meshio.Mesh(ring["points"], [("hexahedron", ring["hexahedra"])],
                                   point_data={"temperature": ring["point_data"]["temperature"]}))
    mesh = tetrender.read(path)
    assert mesh._library_mesh() is mesh._handle  # as read: no copy
    mesh.point_data["height"] = mesh.points[:, 2] * 3
    tets = tetrender.tetrahedralize(mesh)
    assert "height" in tets.point_data
    np.testing.assert_allclose(tets.point_data["height"], tets.points[:, 2] * 3)
    tets.cell_data["id"] = np.arange(tets.num_cells, dtype=np.float64)
    assert not tets._unchanged()


def test_pyvista_legacy_cells_of_mixed_sizes():
    grid = types.SimpleNamespace(points=np.random.default_rng(2).random((12, 3)),
                                 cells=np.array([4, 0, 1, 2, 3, 8, 4, 5, 6, 7, 8, 9, 10, 11, 4, 1, 2, 3, 4]),
                                 celltypes=np.array([10, 12, 10], dtype=np.uint8), point_data={})
    mesh = tetrender.Mesh.from_pyvista(grid)
    np.testing.assert_array_equal(mesh.offsets, [0, 4, 12, 16])
    np.testing.assert_array_equal(mesh.connectivity, [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 1, 2, 3, 4])
    grid.cells = grid.cells[:-1]
    with pytest.raises(tetrender.Error, match="cells has 18 entries, the counts say 19"):
        tetrender.Mesh.from_pyvista(grid)


def test_read_a_time_step_of_a_series(ring, output_dir):
    # A ParaView collection of two .vtu files written by meshio; step 1's temperature doubled.
    for step in (0, 1):
        meshio.write(output_dir / f"ring_{step}.vtu",
                     meshio.Mesh(ring["points"], [("hexahedron", ring["hexahedra"])],
                                 point_data={"temperature": ring["point_data"]["temperature"] * (1 + step)}))
    (output_dir / "ring.pvd").write_text(
        '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
        '<DataSet timestep="0.5" file="ring_0.vtu"/>\n<DataSet timestep="1.5" file="ring_1.vtu"/>\n'
        '</Collection>\n</VTKFile>\n')
    first = tetrender.read(output_dir / "ring.pvd")
    second = tetrender.read(output_dir / "ring.pvd", time_step=1)
    assert first.time_values == second.time_values == [0.5, 1.5]
    assert (first.time_step, second.time_step) == (0, 1)
    np.testing.assert_array_equal(second.point_data["temperature"], 2 * first.point_data["temperature"])
    with pytest.raises(tetrender.Error, match="time step"):
        tetrender.read(output_dir / "ring.pvd", time_step=2)
