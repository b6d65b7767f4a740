"""The examples in examples/python run and do what they say."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import tetrender

EXAMPLES = Path(os.environ.get("TETRENDER_SOURCE_DIR", Path(__file__).resolve().parents[2])) / "examples" / "python"


def run(script: str, *args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(EXAMPLES / script), *args], cwd=cwd,
                          capture_output=True, text=True, check=False, env=os.environ.copy())


def test_render_simulation_writes_the_pipe(output_dir):
    out = output_dir / "pipe.png"
    result = run("render_simulation.py", "-o", str(out), "--size", "160x120", cwd=output_dir)
    assert result.returncode == 0, result.stderr
    assert "15360 hexahedra" in result.stdout
    picture = tetrender.read_image(out)
    assert picture.shape == (120, 160, 3)
    background = np.float32([0.08, 0.08, 0.12])
    covered = (np.abs(picture - background).max(axis=2) > 0.01).mean()
    # Measured 32% of the frame at 640x480; the hot plume is red: some pixels with red > blue.
    assert 0.2 < covered < 0.5, covered
    assert ((picture[..., 0] > picture[..., 2] + 0.1)).sum() > 100


def test_check_sort_passes_and_reports_the_centroid_violations(output_dir):
    result = run("check_sort.py", "--views", "3", "--size", "64", cwd=output_dir)
    assert result.returncode == 0, result.stdout + result.stderr
    rows = {line.split()[0]: line.split() for line in result.stdout.splitlines()[2:]}
    assert rows["exact"][1] == "yes" and rows["exact"][3:] == ["0", "0"]
    # The centroid baseline is no visibility order on the ring: the verifier sees it.
    assert int(rows["centroid"][3]) > 0


def test_check_sort_reads_a_file(output_dir, ring):
    import meshio

    meshio.write(output_dir / "ring.vtu", meshio.Mesh(ring["points"], [("hexahedron", ring["hexahedra"])],
                                                      point_data=ring["point_data"]))
    result = run("check_sort.py", str(output_dir / "ring.vtu"), "--views", "2", "--size", "48",
                 "--methods", "exact", cwd=output_dir)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "384 tets" in result.stdout
