"""What the package's tests share: the CLI of the same build, its outputs, CGAL's meshes."""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("PDESURF_BUILD", ROOT / "build")).resolve()
CLI = BUILD / "pdesurf"
EXAMPLES = sorted((ROOT / "examples").glob("*.json"))


def cli(*args):
    """Runs `pdesurf ARGS` and returns its standard output (a failure fails the test)."""
    result = subprocess.run([str(CLI), *map(str, args)], capture_output=True, text=True,
                            cwd=ROOT)
    assert result.returncode == 0, f"pdesurf {' '.join(map(str, args))}: {result.stderr}"
    return result.stdout


def cli_json(*args):
    return json.loads(cli(*args))


def read_ply(path):
    """A binary PLY as pdesurf writes it (src/io/mesh_write.cpp), read with numpy alone:
    (positions (N, 3) float32, normals (N, 3) float32 or None, triangles (M, 3) int32)."""
    data = pathlib.Path(path).read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    vertices = int(next(l for l in header if l.startswith("element vertex")).split()[-1])
    faces = int(next(l for l in header if l.startswith("element face")).split()[-1])
    columns = sum(l.startswith("property float") for l in header)
    floats = np.frombuffer(data, dtype="<f4", count=vertices * columns, offset=end)
    floats = floats.reshape(vertices, columns)
    face = np.dtype([("n", "u1"), ("v", "<i4", 3)])
    triangles = np.frombuffer(data, dtype=face, count=faces, offset=end + floats.nbytes)
    assert (triangles["n"] == 3).all()
    return floats[:, :3], (floats[:, 3:] if columns == 6 else None), triangles["v"]


@pytest.fixture(scope="session")
def cgal_mesh():
    """The path of one of CGAL's sample meshes (scripts/cgal_data)."""
    def path(name):
        out = subprocess.run([str(ROOT / "scripts/cgal_data"), name, str(BUILD / "cgal-data")],
                             capture_output=True, text=True, check=True)
        return out.stdout.strip()
    return path
