"""Shared pieces of the Python tests (ctest runs them with pytest, tests/CMakeLists.txt sets
PYTHONPATH to build/python, CLOTHSIM_BINARY to clothsim-headless and CLOTHSIM_SOURCE to the tree).
They run only where an OpenGL 4.3 context exists (gpu_test.sh checks first), so the GPU is assumed."""
import os
import subprocess

import pytest

SOURCE = os.environ.get("CLOTHSIM_SOURCE", os.path.join(os.path.dirname(__file__), "..", ".."))
BINARY = os.environ.get("CLOTHSIM_BINARY", os.path.join(SOURCE, "build", "clothsim-headless"))
SPHERE = os.path.join(SOURCE, "scenes", "sphere.json")
# A 7 x 5 cloth: small and odd, as GPU tests keep their grids.
SMALL = {"cloth.num_width_points": 7, "cloth.num_height_points": 5}


def sets(overrides):
    out = []
    for key, value in overrides.items():
        out += ["--set", f"{key}={value}"]
    return out


def simulate(*args):
    """clothsim-headless simulate ARGS; the completed process (it must succeed)."""
    p = subprocess.run([BINARY, "simulate", *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert p.returncode == 0, p.stderr
    return p


@pytest.fixture
def workdir(tmp_path):
    return tmp_path
