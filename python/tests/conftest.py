"""Shared fixtures of tetrender's Python tests: meshes built in numpy, the CLI, an output folder."""

import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import tetrender


def hex_ring(n: int = 6, hole: tuple = (2, 4), layers: int = 2) -> dict:
    """Arrays of an n x n x layers block of unit hexahedra without the middle hole x hole
    columns (not convex), scaled to [0, 1]^2 x [0, layers / n], with a smooth point scalar
    'temperature', a point vector 'velocity' (round the hole) and a cell scalar 'material'."""
    i, j, k = np.meshgrid(np.arange(n + 1), np.arange(n + 1), np.arange(layers + 1), indexing="ij")
    points = np.stack([i.ravel(order="F"), j.ravel(order="F"), k.ravel(order="F")], axis=1) / n
    pid = lambda a, b, c: (c * (n + 1) + b) * (n + 1) + a
    cells = []
    for c in range(layers):
        for b in range(n):
            for a in range(n):
                if hole[0] <= a < hole[1] and hole[0] <= b < hole[1]:
                    continue
                cells.append([pid(a, b, c), pid(a + 1, b, c), pid(a + 1, b + 1, c), pid(a, b + 1, c),
                              pid(a, b, c + 1), pid(a + 1, b, c + 1), pid(a + 1, b + 1, c + 1),
                              pid(a, b + 1, c + 1)])
    cells = np.array(cells, dtype=np.int64)
    x, y, z = points.T
    temperature = 0.5 + 0.4 * np.sin(4.0 * x) * np.cos(3.0 * y) + 0.1 * z
    velocity = np.stack([-(y - 0.5), x - 0.5, np.zeros_like(x)], axis=1)
    return {
        "points": np.ascontiguousarray(points, dtype=np.float64),
        "connectivity": cells.ravel(),
        "offsets": np.arange(0, 8 * len(cells) + 1, 8, dtype=np.int64),
        "types": np.full(len(cells), 12, dtype=np.uint8),
        "point_data": {"temperature": temperature, "velocity": velocity},
        "cell_data": {"material": np.arange(len(cells), dtype=np.float64) % 3},
        "hexahedra": cells,
    }


def scene_dict(mesh, width: int = 96, height: int = 72) -> dict:
    """A scene of `mesh` (a path or a Mesh) coloured by temperature, seen from an oblique eye."""
    return {
        "mesh": mesh,
        "scalar": "temperature",
        "transfer_function": {
            "color": [[0.1, 0.2, 0.3, 0.9], [0.5, 0.9, 0.8, 0.2], [0.9, 1.0, 0.3, 0.1]],
            "opacity": [[0.1, 0.1], [0.9, 0.8]],
            "unit_distance": 0.2,
        },
        "camera": {"position": [1.6, -1.2, 1.5], "focal_point": [0.5, 0.5, 0.17],
                   "view_up": [0, 0, 1], "view_angle": 30.0},
        "image": {"width": width, "height": height, "background": [0.05, 0.05, 0.1]},
    }


def read_pfm(path: Path) -> np.ndarray:
    """A colour PFM as an (H, W, 3) float32 array, row 0 at the top."""
    data = path.read_bytes()
    header, rest = [], data
    for _ in range(3):
        line, rest = rest.split(b"\n", 1)
        header.append(line.decode())
    assert header[0] == "PF", header
    width, height = map(int, header[1].split())
    dtype = "<f4" if float(header[2]) < 0 else ">f4"
    image = np.frombuffer(rest, dtype=dtype, count=width * height * 3).reshape(height, width, 3)
    return image[::-1].astype(np.float32)


@pytest.fixture
def ring():
    return hex_ring()


@pytest.fixture
def output_dir(request) -> Path:
    root = Path(os.environ.get("TETRENDER_TEST_OUTPUT", "/tmp/tetrender-python-tests"))
    path = root / request.node.name
    shutil.rmtree(path, ignore_errors=True)
    path.mkdir(parents=True)
    return path


@pytest.fixture
def cli() -> str:
    """The tetrender command line (TETRENDER_CLI, set by ctest); the test is skipped without it."""
    path = os.environ.get("TETRENDER_CLI")
    if not path or not Path(path).exists():
        pytest.skip("TETRENDER_CLI not set: the command line is not built")
    return path


def run_cli(cli: str, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([cli, *args], capture_output=True, text=True, check=False)


def pytest_configure(config):
    config.addinivalue_line("markers", "realdata: reads ../shared/data (ctest label realdata)")


DATA = Path(os.environ.get("TETRENDER_SOURCE_DIR", Path(__file__).resolve().parents[2])).resolve().parent / "shared" / "data"


@pytest.fixture
def data_dir() -> Path:
    """../shared/data: the test is skipped with a message when it is absent, failed when CI=true
    (as the C++ realdata tests do)."""
    if not DATA.is_dir():
        if os.environ.get("CI") == "true":
            pytest.fail(f"CI=true but the shared data folder is missing: {DATA}")
        pytest.skip(f"no shared data at {DATA}")
    return DATA
