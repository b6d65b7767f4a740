"""Flow volumes from Python: the CLI's picture, and a dye that stays in its domain."""

import json

import meshio
import numpy as np
import pytest

import tetrender
from conftest import read_pfm, run_cli, scene_dict

DYE = {"seed_resolution": 4, "steps": 20, "dt": 0.1}


def test_flow_volume_of_an_in_memory_mesh_is_the_cli_picture(ring, cli, output_dir):
    meshio.write(output_dir / "ring.vtu", meshio.Mesh(ring["points"], [("hexahedron", ring["hexahedra"])],
                                                      point_data=ring["point_data"]))
    scene = scene_dict("ring.vtu")
    scene["flow_volume"] = {"vectors": "velocity", "seed_center": [0.1, 0.5, 0.17],
                            "seed_size": [0.1, 0.1], **DYE}
    (output_dir / "flow.json").write_text(json.dumps(scene))
    result = run_cli(cli, "render", str(output_dir / "flow.json"), "-o", str(output_dir / "cli.pfm"))
    assert result.returncode == 0, result.stderr
    mesh = tetrender.Mesh(ring["points"], ring["connectivity"], ring["offsets"], ring["types"],
                          ring["point_data"])
    picture, dye = tetrender.flow_volume(scene_dict(mesh), "velocity", [0.1, 0.5, 0.17], [0.1, 0.1],
                                         dtype=np.float32, **DYE)
    # Measured: largest difference 0.
    assert np.abs(picture - read_pfm(output_dir / "cli.pfm")).max() == 0.0
    # The dye: 20 layers of tets (measured 1920), inside the ring's box, no older than 2 s.
    assert dye.num_cells > 100 and set(dye.types) == {10}
    assert (dye.points >= -1e-9).all() and (dye.points[:, :2] <= 1 + 1e-9).all()
    assert dye.cell_data["age"].max() <= DYE["steps"] * DYE["dt"] + 1e-9
    # The same dye from the scene file by path.
    by_path, _ = tetrender.flow_volume(output_dir / "flow.json", "velocity", [0.1, 0.5, 0.17],
                                       [0.1, 0.1], dtype=np.float32, **DYE)
    assert np.array_equal(by_path, picture)


def test_flow_volume_errors_carry_the_library_message(ring):
    mesh = tetrender.Mesh(ring["points"], ring["connectivity"], ring["offsets"], ring["types"],
                          ring["point_data"])
    with pytest.raises(tetrender.Error, match="the seed's centre is outside the mesh"):
        tetrender.flow_volume(scene_dict(mesh), "velocity", [5.0, 5.0, 5.0], [0.1, 0.1], **DYE)
    with pytest.raises(tetrender.Error, match=r"no 3-component point array 'temperature' \(vector arrays: velocity\)"):
        tetrender.flow_volume(scene_dict(mesh), "temperature", [0.1, 0.5, 0.17], [0.1, 0.1], **DYE)


def test_spot_noise_and_advection_are_the_clis_frames(ring, cli, output_dir):
    meshio.write(output_dir / "ring.vtu", meshio.Mesh(ring["points"], [("hexahedron", ring["hexahedra"])],
                                                      point_data=ring["point_data"]))
    mesh = tetrender.Mesh(ring["points"], ring["connectivity"], ring["offsets"], ring["types"],
                          ring["point_data"])
    size = ["--size", "64x48"]
    result = run_cli(cli, "spotnoise", str(output_dir / "ring.vtu"), "--scalar", "temperature",
                     "--iso", "0.5", "--vectors", "velocity", "--steps", "3", "--count", "500",
                     *size, "--frames", str(output_dir / "spots"))
    assert result.returncode == 0, result.stderr
    frames, info = tetrender.spot_noise(mesh, "temperature", 0.5, "velocity", steps=3, count=500,
                                        width=64, height=48)
    assert len(frames) == 4 and frames[0].shape == (48, 64, 3) and frames[0].dtype == np.uint8
    assert info["spots"] == 500 and info["dt"] > 0
    for k, frame in enumerate(frames):
        cli_frame = tetrender.read_image(output_dir / "spots" / f"frame_{k:04d}.png")
        # Measured: identical bytes (the PNG's are the rounded floats).
        assert np.array_equal(np.rint(cli_frame * 255).astype(np.uint8), frame), k
    assert not np.array_equal(frames[0], frames[3])  # the spots move
    result = run_cli(cli, "advect", str(output_dir / "ring.vtu"), "--vectors", "velocity",
                     "--steps", "3", "--resolution", "32", *size, "--frames",
                     str(output_dir / "advect"))
    assert result.returncode == 0, result.stderr
    frames, info = tetrender.advect(mesh, "velocity", steps=3, resolution=32, width=64, height=48)
    assert len(frames) == 4 and info["sheet_points"] > 0
    for k, frame in enumerate(frames):
        cli_frame = tetrender.read_image(output_dir / "advect" / f"frame_{k:04d}.png")
        assert np.array_equal(np.rint(cli_frame * 255).astype(np.uint8), frame), k
    with pytest.raises(tetrender.Error, match="no 3-component point array 'temperature'"):
        tetrender.spot_noise(mesh, "temperature", 0.5, "temperature")
    with pytest.raises(tetrender.Error, match="method must be 'backward' or 'forward'"):
        tetrender.advect(mesh, "velocity", method="sideways")


def test_a_2d_mesh_is_the_flow_as_on_the_command_line(cli, output_dir):
    # 8 x 8 quads over [0, 2]^2 at z = 0 with a 2-component velocity (1, 0.5): advect and
    # spot_noise take it as the flow on its plane, frame for frame as the CLI does.
    n = 9
    x, y = np.meshgrid(np.linspace(0, 2, n), np.linspace(0, 2, n))
    points = np.column_stack([x.ravel(), y.ravel(), np.zeros(n * n)])
    quads = [[j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i]
             for j in range(n - 1) for i in range(n - 1)]
    velocity = np.tile([1.0, 0.5], (n * n, 1))
    meshio.write(output_dir / "flow2d.vtu",
                 meshio.Mesh(points, [("quad", np.array(quads))], point_data={"v": velocity}))
    mesh = tetrender.read(output_dir / "flow2d.vtu")
    size = ["--size", "48x48"]
    result = run_cli(cli, "advect", str(output_dir / "flow2d.vtu"), "--vectors", "v", "--steps",
                     "3", "--resolution", "32", *size, "--frames", str(output_dir / "advect2d"))
    assert result.returncode == 0, result.stderr
    assert "2D mesh: the flow on its plane" in result.stdout
    frames, info = tetrender.advect(mesh, "v", steps=3, resolution=32, width=48, height=48)
    assert info["mean_speed"] == pytest.approx(np.hypot(1.0, 0.5))
    for k, frame in enumerate(frames):
        cli_frame = tetrender.read_image(output_dir / "advect2d" / f"frame_{k:04d}.png")
        assert np.array_equal(np.rint(cli_frame * 255).astype(np.uint8), frame), k
    assert not np.array_equal(frames[0], frames[3])
    result = run_cli(cli, "spotnoise", str(output_dir / "flow2d.vtu"), "--vectors", "v",
                     "--steps", "2", "--count", "300", *size, "--frames",
                     str(output_dir / "spots2d"))
    assert result.returncode == 0, result.stderr
    frames, info = tetrender.spot_noise(mesh, "", 0.0, "v", steps=2, count=300, width=48,
                                        height=48)
    assert info["spots"] == 300
    for k, frame in enumerate(frames):
        cli_frame = tetrender.read_image(output_dir / "spots2d" / f"frame_{k:04d}.png")
        assert np.array_equal(np.rint(cli_frame * 255).astype(np.uint8), frame), k


def test_flow_volume_without_a_seed_chooses_it_as_the_scene_file_does(ring, cli, output_dir):
    # No seed_center, seed_size or dt: the library chooses them from the flow, for the scene
    # file on the command line and for Python alike.
    meshio.write(output_dir / "ring.vtu", meshio.Mesh(ring["points"], [("hexahedron", ring["hexahedra"])],
                                                      point_data=ring["point_data"]))
    scene = scene_dict("ring.vtu")
    scene["flow_volume"] = {"vectors": "velocity", "seed_resolution": 4, "steps": 10}
    (output_dir / "chosen.json").write_text(json.dumps(scene))
    result = run_cli(cli, "render", str(output_dir / "chosen.json"), "-o",
                     str(output_dir / "chosen.pfm"))
    assert result.returncode == 0, result.stderr
    assert "seed centre chosen" in result.stderr and "dt chosen" in result.stderr
    picture, dye = tetrender.flow_volume(output_dir / "chosen.json", "velocity", dtype=np.float32,
                                         seed_resolution=4, steps=10)
    assert np.array_equal(picture, read_pfm(output_dir / "chosen.pfm"))
    assert dye.num_cells > 0
