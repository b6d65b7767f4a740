"""Real files through Python (ctest label realdata): tetrender.read against meshio's own reader,
and a mesh handed over from meshio's arrays rendering the CLI's picture of the file."""

import meshio
import numpy as np
import pytest

import tetrender
from conftest import read_pfm, run_cli

pytestmark = pytest.mark.realdata

# The shared .vtu files meshio reads (not can.vtu: meshio 7.0 cannot find its appended data).
VTU = ["bluntfin/bluntfin.vtu", "combustor/combustor.vtu", "fea_bracket/dataset.vtu",
       "lox_post/lox_post.vtu", "mfem_escher/escher.vtu", "mfem_fichera_mixed/fichera-mixed.vtu"]


def cells_by_type(mesh):
    """type -> the cells' node lists as sorted rows (meshio groups cells by type)."""
    out = {}
    for t in np.unique(mesh.types):
        index = np.flatnonzero(mesh.types == t)
        size = mesh.offsets[index[0] + 1] - mesh.offsets[index[0]]
        rows = mesh.connectivity[mesh.offsets[index][:, None] + np.arange(size)]
        out[int(t)] = rows[np.lexsort(rows.T[::-1])]
    return out


@pytest.mark.parametrize("name", VTU)
def test_read_agrees_with_meshio(data_dir, name):
    path = data_dir / name
    ours = tetrender.read(path)
    theirs = tetrender.Mesh.from_meshio(meshio.read(path), volume_only=False)
    # Measured: every point, cell and point array equal on all six files.
    np.testing.assert_array_equal(ours.points, theirs.points)
    a, b = cells_by_type(ours), cells_by_type(theirs)
    assert a.keys() == b.keys()
    for t in a:
        np.testing.assert_array_equal(a[t], b[t])
    assert set(ours.point_data) == set(theirs.point_data)
    for key, values in ours.point_data.items():
        np.testing.assert_array_equal(values.reshape(len(values), -1),
                                      np.asarray(theirs.point_data[key]).reshape(len(values), -1))


@pytest.mark.parametrize("name,scalar", [("bluntfin/bluntfin.vtu", "Density"),
                                         ("lox_post/lox_post.vtu", "StagnationEnergy")])
def test_meshio_arrays_render_the_cli_picture_of_the_file(data_dir, cli, output_dir, name, scalar):
    out = output_dir / "cli.pfm"
    result = run_cli(cli, "render", str(data_dir / name), "--scalar", scalar, "--size", "120x90",
                     "--legend", "off", "-o", str(out))
    assert result.returncode == 0, result.stderr
    mesh = tetrender.Mesh.from_meshio(meshio.read(data_dir / name))
    picture = tetrender.render(tetrender.Scene.quick(mesh, scalar, width=120, height=90),
                               dtype=np.float32)
    expected = read_pfm(out)
    assert (np.abs(expected).max(axis=2) > 0.01).mean() > 0.05  # the object is in the picture
    # Measured: largest difference 0 on both (meshio's arrays, VTK's file: the same picture).
    assert np.abs(picture - expected).max() == 0.0
