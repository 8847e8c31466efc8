"""hooke.run is `hooke run`: the same files, the same summary, and a
Simulation stepped from Python reaches the same states to the last bit."""

import json

import numpy as np
import pytest

import hooke
from conftest import TIMING_KEYS, frames, read_ply


def test_run_returns_the_summary_it_writes(default_run):
    summary, out = default_run
    assert summary == json.loads((out / "summary.json").read_text())
    assert summary["scene"] == "stiff-cloth"
    assert summary["steps"] == summary["steps_planned"] == 210
    assert summary["error"] is None and summary["finite"]
    assert summary["implicit_settings"]["solver"] == "auto"


def test_python_and_command_line_write_the_same_run(default_run, command_line_run):
    summary, out = default_run
    written = frames(out)
    assert [f.name for f in written] == [f.name for f in frames(command_line_run)]
    assert len(written) == summary["frames"] == 211
    for a in written:
        assert a.read_bytes() == (command_line_run / a.name).read_bytes(), a.name
    other = json.loads((command_line_run / "summary.json").read_text())
    same = lambda s: {k: v for k, v in s.items() if k not in TIMING_KEYS}  # noqa: E731
    assert same(summary) == same(other)


def test_stepping_from_python_reaches_every_frame_to_the_last_bit(default_run):
    summary, out = default_run
    written = frames(out)
    sim = hooke.Simulation()
    assert np.array_equal(sim.positions.astype(np.float32), read_ply(written[0]))
    newton = linear_solves = rejected = 0
    for k in range(1, summary["steps"] + 1):
        report = sim.step()
        newton += report["newton_iterations"]
        linear_solves += report["linear_solves"]
        rejected += report["rejected_steps"]
        # One frame per step: the frame file holds the state as f32.
        frame = read_ply(written[k])
        assert np.array_equal(sim.positions.astype(np.float32).view(np.uint32), frame.view(np.uint32)), k
    # The energy after the last step, velocities included, to the last bit.
    assert sim.energy()["total"] == summary["energy_final"]
    assert sim.report["energy"] == summary["energy_final"]
    assert sim.time == summary["time"]
    assert newton / summary["steps"] == summary["newton_iterations_mean"]
    assert (linear_solves, rejected) == (summary["linear_solves"], summary["rejected_steps"])


def test_a_run_that_stops_early_raises_with_its_summary(tmp_path):
    # Explicit Euler at h ω = 1 gains energy 2× a step: it diverges.
    scene = hooke.Scene.builtin("oscillator")
    scene.dt = 1.0
    with pytest.raises(hooke.RunError, match="the run stopped after") as caught:
        hooke.run(scene, tmp_path, gif=False, integrator="explicit-euler", duration=1e4)
    summary = caught.value.summary
    assert summary["steps"] < summary["steps_planned"]
    assert summary["finite"] is False and summary["error"]


def test_usd_and_gif_can_be_left_out(tmp_path):
    summary = hooke.run("chain", tmp_path, gif=False, usd=False, duration=0.1)
    assert summary["frames"] == len(frames(tmp_path))
    assert not (tmp_path / "animation.usda").exists() and not (tmp_path / "animation.gif").exists()
    assert (tmp_path / "preview.png").exists()
