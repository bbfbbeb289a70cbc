"""`import clothsim`: the Simulation API against the command line, on both backends."""
import json
import os
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import clothsim
from conftest import BINARY, SMALL, SPHERE, sets, simulate


@pytest.mark.parametrize("backend", ["cpu", "gpu"])
def test_positions_after_10_frames_equal_the_command_lines_export(backend, workdir):
    s = clothsim.Simulation(SPHERE, backend=backend, overrides=SMALL)
    s.step(frames=10)
    x = s.positions()
    assert x.shape == (35, 3) and x.dtype == np.float64 and s.frame == 10
    pc2 = workdir / "run.pc2"
    simulate(SPHERE, "--frames", "10", "--backend", backend, "--export", str(pc2), *sets(SMALL))
    cache = clothsim.read_pc2(pc2)
    assert cache.shape == (11, 35, 3)
    # The point cache holds float32: the module's doubles, rounded, are those bits exactly.
    assert np.array_equal(x.astype(np.float32), cache[10])
    if backend == "gpu":  # the GPU computes in float, so its doubles are the floats themselves
        assert np.array_equal(x, cache[10].astype(np.float64))
    # The cloth fell: the test would fail on a module that returned the initial state.
    assert not np.array_equal(cache[10], cache[0])


def test_the_cpu_positions_are_the_saved_states_doubles(workdir):
    s = clothsim.Simulation(SPHERE, backend="cpu", overrides=SMALL)
    s.step(10)
    state = workdir / "s.state"
    simulate(SPHERE, "--frames", "10", "--backend", "cpu", "--save-state", str(state), *sets(SMALL))
    data = state.read_bytes()
    # docs/export.md: an 88-byte header whose u32s at 56 and 60 are the lengths of the scene's
    # and the backend's names, the names, then the positions, 4 doubles per particle.
    names = int(np.frombuffer(data, dtype="<u4", offset=56, count=2).sum())
    pos = np.frombuffer(data, dtype="<f8", offset=88 + names, count=35 * 4).reshape(35, 4)[:, :3]
    assert np.array_equal(s.positions(), pos)


def test_a_dict_scene_with_overrides_is_the_file_with_set(workdir):
    with open(SPHERE) as f:
        scene = json.load(f)
    a = clothsim.Simulation(scene, backend="cpu", overrides={**SMALL, "sphere.friction": 0.9})
    b = clothsim.Simulation(SPHERE, backend="cpu", overrides=[f"{k}={v}" for k, v in {**SMALL, "sphere.friction": 0.9}.items()])
    c = clothsim.Simulation(SPHERE, backend="cpu", overrides=SMALL)
    for s in (a, b, c):
        s.step(120)
    assert np.array_equal(a.positions(), b.positions())
    assert not np.array_equal(a.positions(), c.positions())  # the friction override took effect


def test_velocities_and_set_positions():
    s = clothsim.Simulation(SPHERE, backend="gpu", overrides={**SMALL, "cloth.damping": 0})
    s.step(5)
    v = s.velocities()
    # Free fall from rest, undamped, for 5 frames of 1/90 s: -g t, to the substep's first order.
    assert v.shape == (35, 3)
    assert np.allclose(v[:, 1], -9.8 * 5 / 90, rtol=2e-2)
    x = s.positions() + np.array([0.0, 0.25, 0.0])
    s.set_positions(x.astype(np.float32))  # any float type is taken
    assert np.array_equal(s.positions(), x.astype(np.float32).astype(np.float64))
    assert np.array_equal(s.velocities(), v)  # velocities kept
    with pytest.raises(ValueError, match=r"shape \(35, 3\)"):
        s.set_positions(np.zeros((34, 3)))


def test_stats_are_the_command_lines(workdir):
    s = clothsim.Simulation(SPHERE, backend="cpu", overrides=SMALL)
    s.step(30)
    st = s.stats()
    out = workdir / "stats.json"
    simulate(SPHERE, "--frames", "30", "--backend", "cpu", "--stats-json", str(out), *sets(SMALL))
    cli = json.loads(out.read_text())
    for key in ("max_stretch", "p99_stretch", "kinetic_energy_J", "max_speed_m_s", "sphere_clearance_m",
                "self_intersections", "frames", "substeps", "time_s", "finite", "particles"):
        assert st[key] == cli[key], key
    assert st["frame"] == 30 and st["finite"] is True and st["sphere_clearance_m"][0] > 0


def test_export_and_render(workdir):
    s = clothsim.Simulation(SPHERE, backend="gpu", overrides=SMALL)
    s.step(3)
    obj = workdir / "cloth.obj"
    s.export(obj)
    v = [l for l in obj.read_text().splitlines() if l.startswith("v ")]
    assert len(v) == 35
    png = workdir / "cloth.png"
    s.render(png, shader="Normal", size=(64, 48))
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(ValueError, match="ending in .png"):
        s.render(workdir / "cloth.jpg")
    with pytest.raises(ValueError, match="Wireframe"):
        s.render(png, shader="Glossy")
    cpu = clothsim.Simulation(SPHERE, backend="cpu", overrides=SMALL)
    cpu.render(workdir / "cpu.png", size=(64, 48))  # the CPU backend draws through a context of its own
    assert (workdir / "cpu.png").exists()


def test_bad_input_is_value_error_with_the_command_lines_message(workdir):
    with pytest.raises(ValueError, match=r"sphere.json: cloth.ks: expected a spring constant >= 0"):
        clothsim.Simulation(SPHERE, backend="cpu", overrides={"cloth.ks": -1})
    with pytest.raises(ValueError, match="no_such_scene.json"):
        clothsim.Simulation(str(workdir / "no_such_scene.json"), backend="cpu")
    with open(SPHERE) as f:
        scene = json.load(f)
    scene["cloth"]["num_width_points"] = "many"
    with pytest.raises(ValueError, match="<dict>: cloth.num_width_points: expected an integer"):
        clothsim.Simulation(scene, backend="cpu")
    with pytest.raises(ValueError, match="backend"):
        clothsim.Simulation(SPHERE, backend="tpu")
    with pytest.raises(ValueError, match="not a JSON value"):
        clothsim.Simulation(SPHERE, backend="cpu", overrides={"cloth.ks": float("nan")})
    s = clothsim.Simulation(SPHERE, backend="cpu", overrides=SMALL)
    with pytest.raises(ValueError, match=r"export .*cloth.pc2: expected a file name ending in .obj"):
        s.export(workdir / "cloth.pc2")
    with pytest.raises(ValueError, match="no_such_folder"):
        s.export(workdir / "no_such_folder" / "cloth.obj")
    # A file the run did not name is never touched: a symbolic link named is replaced, not followed.
    target = workdir / "keep.txt"
    target.write_text("mine")
    os.symlink(target, workdir / "link.obj")
    s.export(workdir / "link.obj")
    assert target.read_text() == "mine" and not os.path.islink(workdir / "link.obj")


def test_a_divergence_raises_divergence_error():
    s = clothsim.Simulation(SPHERE, backend="cpu", overrides={**SMALL, "simulation.gravity": [0, -1e9, 0]})
    with pytest.raises(clothsim.DivergenceError, match="diverged at frame 1"):
        s.step(20)
    assert s.frame == 1  # the state stays at the frame that failed
    assert isinstance(clothsim.DivergenceError("x"), RuntimeError)


def test_no_context_is_runtime_error_suggesting_the_cpu():
    code = ("import clothsim\n"
            "try:\n  clothsim.Simulation(%r, backend='gpu')\n"
            "except RuntimeError as e:\n  print('RuntimeError', e)\n" % SPHERE)
    env = dict(os.environ, __EGL_VENDOR_LIBRARY_FILENAMES="/nonexistent.json")
    p = subprocess.run([sys.executable, "-c", code], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert p.returncode == 0, p.stderr
    assert p.stdout.startswith("RuntimeError no OpenGL 4.3 context"), p.stdout
    assert 'backend="cpu"' in p.stdout


def test_the_gil_is_released_while_stepping():
    s = clothsim.Simulation(SPHERE, backend="cpu", overrides={"cloth.num_width_points": 31,
                                                              "cloth.num_height_points": 31})
    ended = {}

    def run():
        s.step(frames=120)
        ended["step"] = time.monotonic()

    t = threading.Thread(target=run)
    t.start()
    time.sleep(0.05)  # let the thread enter step()
    total = sum(i * i for i in range(20000))  # Python work, which needs the GIL
    ended["main"] = time.monotonic()
    t.join()
    assert total > 0
    # Held through the step, the GIL would let this thread's work end only after the step.
    assert ended["main"] < ended["step"]
