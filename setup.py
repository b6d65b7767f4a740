"""`pip install .`: the Python module tetrender (docs/python.md), built by this CMake project.

Works offline with Debian's setuptools and pip (no build isolation, nothing downloaded):

    TETRENDER_BUILD_DIR=build python3 -m pip install --no-build-isolation --no-index .

TETRENDER_BUILD_DIR names a configured build folder whose target tetrender_python is built (and
its extension packaged); without it the library is configured and built in build-pip/cmake (minutes:
CMAKE_BUILD_PARALLEL_LEVEL sets the jobs). The pure-Python part comes from python/tetrender.
"""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
VERSION = re.search(r"project\(tetrender VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text()).group(1)
# Everything pip and setuptools write goes under build-pip/ (ignored by git; TETRENDER_PIP_WORK
# moves it), out of the sources and of the build/ folder that scripts/test.sh uses.
WORK = Path(os.environ.get("TETRENDER_PIP_WORK", ROOT / "build-pip")).resolve()
EGG_BASE = WORK / "egg-info"


class CMakeBuild(build_ext):
    """Builds tetrender._core with CMake instead of compiling sources itself."""

    def build_extension(self, ext: Extension) -> None:
        build = Path(os.environ.get("TETRENDER_BUILD_DIR", WORK / "cmake")).resolve()
        if not (build / "CMakeCache.txt").exists():
            subprocess.check_call([
                "cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                f"-DPython_EXECUTABLE={sys.executable}", "-DTETRENDER_PYTHON=ON",
                "-DTETRENDER_BUILD_TESTS=OFF", "-DTETRENDER_BUILD_BENCH=OFF",
                "-DTETRENDER_BUILD_VIEWER=OFF", "-DTETRENDER_BUILD_APPS=OFF"])
        subprocess.check_call(["cmake", "--build", str(build), "--target", "tetrender_python"])
        built = sorted((build / "python" / "tetrender").glob("_core*.so"))
        if not built:
            raise RuntimeError(f"{build}: the build made no tetrender/_core*.so (is TETRENDER_PYTHON on?)")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], target)
        # TetGen runs in a program of its own, looked for next to the module (README: Licences).
        worker = build / "mesh" / "copyleft" / "tetrender-tetgen-worker"
        if worker.exists():
            shutil.copy2(worker, target.parent / worker.name)


EGG_BASE.mkdir(parents=True, exist_ok=True)
setup(
    name="tetrender",
    version=VERSION,
    description="Volume rendering of unstructured meshes (numpy in, pictures out)",
    license="BSD-3-Clause",
    python_requires=">=3.9",
    package_dir={"": "python"},
    packages=["tetrender"],
    ext_modules=[Extension("tetrender._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"egg_info": {"egg_base": str(EGG_BASE)}, "build": {"build_base": str(WORK / "setuptools")}},
    zip_safe=False,
)
