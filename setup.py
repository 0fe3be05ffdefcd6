"""`pip install .`: the Python package pdesurf, its compiled core built by CMake.

An existing CMake build of this checkout (build/, or $PDESURF_BUILD) configured for the same
Python is reused (`make build` made it); otherwise a build of the module alone is configured
under build/python-pip. docs/python.md gives the offline command for Debian's python3.
"""

import os
import pathlib
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent
PIP_BUILD = ROOT / "build/python-pip"


class CMakeBuild(build_ext):
    """Builds pdesurf._core with the project's CMake and copies it where setuptools wants it."""

    def build_extension(self, ext):
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        build = pathlib.Path(os.environ.get("PDESURF_BUILD", ROOT / "build")).resolve()
        if not list((build / "python/pdesurf").glob(f"_core{suffix}")):
            # No build for this Python: one of the module alone.
            build = PIP_BUILD / "cmake"
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build),
                            "-DCMAKE_BUILD_TYPE=Release", "-DPDESURF_PYTHON=ON",
                            "-DPDESURF_BUILD_TESTS=OFF", "-DPDESURF_BUILD_BENCH=OFF",
                            f"-DPython_EXECUTABLE={sys.executable}"], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "pdesurf_python", "-j",
                        str(os.cpu_count() or 1)], check=True)
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(build / "python/pdesurf" / f"_core{suffix}", target)


PIP_BUILD.mkdir(parents=True, exist_ok=True)
setup(
    packages=["pdesurf"],
    package_dir={"": "python"},
    package_data={"pdesurf": ["*.pyi", "py.typed"]},
    ext_modules=[Extension("pdesurf._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": str(PIP_BUILD)}, "egg_info": {"egg_base": str(PIP_BUILD)}},
)
