"""clothsim from Python: one simulation at a time (Simulation) and sweeps of many (sweep).

    import clothsim
    s = clothsim.Simulation("scenes/sphere.json", backend="gpu", overrides={"cloth.ks": 2000})
    s.step(frames=30)
    x = s.positions()          # (N, 3) float64
    print(s.stats()["max_stretch"])

docs/python.md is the reference; docs/sweeps.md describes sweeps.
"""
import json
import os

from . import _clothsim
from ._clothsim import DivergenceError

__all__ = ["Simulation", "DivergenceError", "sweep", "override_strings", "read_pc2"]


def override_strings(overrides):
    """{"cloth.ks": 2000, "sphere[0].friction": 0.4} -> ["cloth.ks=2000", ...], as --set takes them.

    Each value is written as JSON, so numbers, booleans, lists and strings mean what they do in
    a scene file; a list or tuple of "KEY=VALUE" strings is passed through unchanged.
    """
    if overrides is None:
        return []
    if isinstance(overrides, dict):
        out = []
        for key, value in overrides.items():
            if not isinstance(key, str) or not key:
                raise ValueError(f"overrides: every key must be a scene key path such as 'cloth.ks', got {key!r}")
            try:
                text = json.dumps(value, allow_nan=False)
            except (TypeError, ValueError) as e:
                raise ValueError(f"overrides: {key}: {value!r} is not a JSON value ({e})") from None
            out.append(f"{key}={text}")
        return out
    if isinstance(overrides, (list, tuple)) and all(isinstance(o, str) for o in overrides):
        return list(overrides)
    raise ValueError("overrides: expected a dict {key: value} or a list of 'key=value' strings")


class Simulation:
    """A scene's cloth, stepped a frame at a time on the GPU (compute shaders) or the CPU reference.

    scene: a scene file's path, or the scene itself as a dict (the scene file's JSON; relative
    file names in it are relative to the working directory). backend: "gpu" or "cpu".
    overrides: {key: value} applied like --set key=value. Bad input raises ValueError with the
    command line's message; backend="gpu" without an OpenGL 4.3 context raises RuntimeError.
    """

    def __init__(self, scene, backend="gpu", overrides=None):
        sets = override_strings(overrides)
        if isinstance(scene, dict):
            try:
                text = json.dumps(scene, allow_nan=False)
            except (TypeError, ValueError) as e:
                raise ValueError(f"scene: the dict is not JSON ({e})") from None
            self._s = _clothsim.Session(text, True, backend, sets)
        elif isinstance(scene, (str, os.PathLike)):
            self._s = _clothsim.Session(os.fspath(scene), False, backend, sets)
        else:
            raise ValueError(f"scene: expected a file path or a dict, got {type(scene).__name__}")

    def step(self, frames=1):
        """Simulates `frames` rendered frames (each the scene's substeps). The GIL is released.

        A frame that fails the divergence check raises DivergenceError; the state stays at it.
        """
        if isinstance(frames, bool) or not isinstance(frames, int) or frames < 0:
            raise ValueError(f"step: frames must be a non-negative integer, got {frames!r}")
        self._s.step(frames)

    def positions(self):
        """The particles' positions, an (N, 3) float64 array (a copy)."""
        return self._s.positions()

    def velocities(self):
        """The particles' velocities (x - x_prev) / dt of the last substep, (N, 3) float64."""
        return self._s.velocities()

    def set_positions(self, positions):
        """Moves every particle to `positions` ((N, 3), any float type); velocities are kept."""
        self._s.set_positions(positions)

    def stats(self):
        """The --stats figures as a dict (docs/python.md lists the keys)."""
        return json.loads(self._s.stats())

    def export(self, path):
        """Writes the cloth as it is now to an OBJ file (as simulate --export FILE.obj)."""
        self._s.export(os.fspath(path))

    def render(self, path, shader="Phong", size=(800, 600)):
        """Renders the cloth as it is now to a PNG with the default camera and the demo look."""
        try:
            w, h = (int(v) for v in size)
        except (TypeError, ValueError):
            raise ValueError(f"render: size must be (width, height), got {size!r}") from None
        self._s.render(os.fspath(path), str(shader), w, h)

    @property
    def frame(self):
        """Frames simulated since the initial state."""
        return self._s.frame

    @property
    def particles(self):
        return self._s.particles

    @property
    def backend(self):
        return self._s.backend

    @property
    def dt(self):
        """The substep length in seconds."""
        return self._s.dt

    def __repr__(self):
        return f"<clothsim.Simulation {self._s.source}: {self.particles} particles, frame {self.frame}, {self.backend}>"


def read_pc2(path):
    """A PC2 point cache (what --export FILE.pc2 and each sweep run write) as a numpy array of
    shape (samples, points, 3), float32."""
    import numpy as np

    with open(path, "rb") as f:
        data = f.read()
    if len(data) < 32 or data[:12] != b"POINTCACHE2\0":
        raise ValueError(f"{path}: not a PC2 point cache (no POINTCACHE2 header)")
    points, samples = int.from_bytes(data[16:20], "little"), int.from_bytes(data[28:32], "little")
    if len(data) < 32 + 12 * points * samples:
        raise ValueError(f"{path}: {points} points x {samples} samples need {32 + 12 * points * samples} bytes, "
                         f"the file has {len(data)}")
    return np.frombuffer(data, dtype="<f4", offset=32, count=3 * points * samples).reshape(samples, points, 3)


def sweep(*args, **kwargs):
    """Runs a sweep on Dask (see clothsim.sweeps.sweep and docs/sweeps.md)."""
    from .sweeps import sweep as run
    return run(*args, **kwargs)
