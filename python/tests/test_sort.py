"""Visibility orders from Python, checked by the library's independent verifier."""

import numpy as np
import pytest

import tetrender
from conftest import scene_dict


@pytest.fixture
def scene(ring):
    mesh = tetrender.Mesh(ring["points"], ring["connectivity"], ring["offsets"], ring["types"],
                          ring["point_data"])
    return tetrender.Scene(scene_dict(mesh, 128, 96))


def test_exact_order_of_a_non_convex_mesh_passes_the_verifier(scene):
    result = tetrender.sort(scene, "exact")
    tets = scene.mesh()
    assert result.order.dtype == np.uint32
    assert sorted(result.order) == list(range(tets.num_cells))  # every real tet once
    check = tetrender.verify_order(scene, result)
    # Measured at 128x96: 5,300 rays, 37,000 consecutive pairs, no violation.
    assert check.rays > 2000 and check.pairs > 10000
    assert check.ok and result.exact, (check, result.note)


def test_the_verifier_catches_wrong_orders(scene):
    order = tetrender.sort(scene, "exact").order
    backwards = tetrender.verify_order(scene, order[::-1])
    assert backwards.violations == backwards.pairs > 0
    # Centroid distance is no visibility order on this ring: measured 276 violations of 37,477 pairs at 128x96.
    centroid = tetrender.sort(scene, "centroid")
    assert not centroid.exact
    assert tetrender.verify_order(scene, centroid).violations > 0
    missing = tetrender.verify_order(scene, order[1:])
    assert missing.missing_cells > 0


def test_order_ids_are_checked(scene):
    n = scene.mesh().num_cells
    with pytest.raises(tetrender.Error, match=rf"order\[1\] = {n} is not a cell of the volume's mesh \(it has {n} tets\)"):
        tetrender.verify_order(scene, [0, n])
    with pytest.raises(tetrender.Error, match="unknown"):
        tetrender.sort(scene, "bubble")
    with pytest.raises(tetrender.Error, match=r"volume 3 out of range \(the scene has 1\)"):
        tetrender.sort(scene, "exact", volume=3)
