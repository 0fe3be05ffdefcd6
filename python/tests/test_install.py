"""The package as a user installs it: `pip install .` (offline, docs/python.md) and
`cmake --install` both give a package that imports outside the repository and tessellates
exactly as the package of the build does."""

import os
import subprocess
import sys

import pdesurf
from conftest import BUILD, ROOT

# What the installed package is asked to compute, in a fresh interpreter outside the tree:
# the mug's positions at resolution 9, as hex, with the module's path.
PROBE = (
    "import sys, pdesurf\n"
    "mesh = pdesurf.load(sys.argv[1]).solve().tessellate(9)\n"
    "print(pdesurf.__file__)\n"
    "print(mesh.positions.tobytes().hex())\n"
)


def probe(python, cwd, env=None):
    """(the imported package's __init__.py, the mug's positions as bytes) from `python`."""
    result = subprocess.run([str(python), "-c", PROBE, str(ROOT / "examples/mug.json")],
                            capture_output=True, text=True, cwd=cwd, env=env)
    assert result.returncode == 0, result.stderr
    where, positions = result.stdout.split()
    return where, bytes.fromhex(positions)


def expected():
    return pdesurf.load(ROOT / "examples/mug.json").solve().tessellate(9).positions.tobytes()


def test_pip_installs_the_package_offline_into_a_virtual_environment(tmp_path):
    venv = tmp_path / "env"
    made = subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)],
                          capture_output=True, text=True)
    assert made.returncode == 0, f"python3 -m venv (scripts/setup installs python3-venv): " \
        f"{made.stderr}"
    env = dict(os.environ, PDESURF_BUILD=str(BUILD))
    env.pop("PYTHONPATH", None)  # the installed package, not the build's
    pip = subprocess.run([str(venv / "bin/pip"), "install", "-q", "--no-build-isolation",
                          "--no-index", str(ROOT)], capture_output=True, text=True, env=env)
    assert pip.returncode == 0, pip.stderr
    where, positions = probe(venv / "bin/python", tmp_path, env)
    assert where.startswith(str(venv)), where
    assert positions == expected()


def test_cmake_install_puts_an_importable_package_under_the_prefix(tmp_path):
    prefix = tmp_path / "prefix"
    # The whole install (headers, libraries, CLI and the package): a few seconds of copying.
    installed = subprocess.run(["cmake", "--install", str(BUILD), "--prefix", str(prefix)],
                               capture_output=True, text=True)
    assert installed.returncode == 0, installed.stderr
    env = dict(os.environ, PYTHONPATH=str(prefix / "lib/python3/dist-packages"))
    where, positions = probe(sys.executable, tmp_path, env)
    assert where.startswith(str(prefix)), where
    assert positions == expected()
