"""`cmake --install` puts an importable package under <prefix>/lib/python3/dist-packages."""

import os
import subprocess
import sys
from pathlib import Path

import pytest


def test_installed_package_imports_and_renders(output_dir):
    build = os.environ.get("TETRENDER_BUILD_DIR")
    cmake = os.environ.get("CMAKE_COMMAND", "cmake")
    if not build:
        pytest.skip("TETRENDER_BUILD_DIR not set (ctest sets it)")
    prefix = output_dir / "prefix"
    # Only python/'s install rules (the library's headers and archives are not needed here).
    installed = subprocess.run([cmake, f"-DCMAKE_INSTALL_PREFIX={prefix}", "-P",
                                str(Path(build) / "python" / "cmake_install.cmake")],
                               capture_output=True, text=True, check=False)
    assert installed.returncode == 0, installed.stderr
    site = prefix / "lib" / "python3" / "dist-packages"
    code = ("import numpy as np, tetrender; print(tetrender.__file__); "
            "m = tetrender.Mesh(np.eye(4, 3, -1), [0, 1, 2, 3], None, [10], {'s': np.arange(4.0)}); "
            "print(tetrender.tetrahedralize(m).num_cells)")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(site)
    run = subprocess.run([sys.executable, "-c", code], cwd=output_dir, env=env,
                         capture_output=True, text=True, check=False)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.split()
    assert Path(lines[0]).resolve().is_relative_to(site.resolve()), lines[0]
    assert lines[1] == "1"


def test_pip_install_offline_with_debian_setuptools(output_dir):
    build = os.environ.get("TETRENDER_BUILD_DIR")
    source = os.environ.get("TETRENDER_SOURCE_DIR")
    if not build or not source:
        pytest.skip("TETRENDER_BUILD_DIR or TETRENDER_SOURCE_DIR not set (ctest sets them)")
    if subprocess.run([sys.executable, "-m", "pip", "--version"], capture_output=True).returncode != 0:
        pytest.skip("no pip for this Python (Debian: python3-pip)")
    target = output_dir / "site"
    env = dict(os.environ, TETRENDER_PIP_WORK=str(output_dir / "pip-work"), PIP_NO_INPUT="1")
    # No build isolation, no index: nothing is downloaded; the build folder's target is reused.
    installed = subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--no-build-isolation",
                                "--no-index", "--target", str(target), source],
                               env=env, capture_output=True, text=True, check=False)
    assert installed.returncode == 0, installed.stdout + installed.stderr
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(target)
    code = "import tetrender; print(tetrender.__file__); print(tetrender.Mesh([[0, 0, 0]]).num_points)"
    run = subprocess.run([sys.executable, "-c", code], cwd=output_dir, env=env,
                         capture_output=True, text=True, check=False)
    assert run.returncode == 0, run.stderr
    path, count = run.stdout.split()
    assert Path(path).resolve().is_relative_to(target.resolve()) and count == "1"
    # The sources stay clean: setuptools wrote under TETRENDER_PIP_WORK only.
    assert not (Path(source) / "python" / "tetrender.egg-info").exists()
