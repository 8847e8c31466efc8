"""Each kind of bad input raises a hooke exception naming what is wrong,
with the command line's message; nothing crashes."""

import numpy as np
import pytest

import hooke

TWO = dict(positions=[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], masses=1.0)


def test_the_exceptions_are_one_hierarchy():
    for error in [hooke.SceneError, hooke.SettingsError, hooke.StateError, hooke.StepError,
                  hooke.RunError]:
        assert issubclass(error, hooke.HookeError) and issubclass(error, Exception)


@pytest.mark.parametrize(
    "change, message",
    [
        (dict(positions=[[0.0, 0.0], [1.0, 0.0]]), r"positions: expected an array of shape \(n, 3\), got shape \(2, 2\)"),
        (dict(positions=[[0.0, 0.0, 0.0], [np.nan, 0.0, 0.0]]), r"positions: row 1 is not finite"),
        (dict(positions="cloth"), r"positions: not an array of numbers"),
        (dict(masses=[1.0, 2.0, 3.0]), r"masses: expected a number or an array of shape \(2,\), got shape \(3,\)"),
        (dict(masses=[1.0, -1.0]), r"particle 1"),
        (dict(springs=[[0, 5]], stiffness=1.0), r"springs: row 0: particle 5 does not exist \(there are 2 particles\)"),
        (dict(springs=[[0, 1]]), r"stiffness: required with springs"),
        (dict(springs=[[0, 1]], stiffness=[1.0, 2.0]), r"stiffness: expected a number or an array of shape \(1,\)"),
        (dict(springs=[[0, 1]], stiffness=-1.0), r"spring 0"),
        (dict(pins=[2]), r"pins: item 0: particle 2 does not exist"),
        (dict(triangles=[[0, 1]]), r"triangles: expected an array of shape \(m, 3\)"),
        (dict(obstacles=[{"shape": "cone"}]), r'obstacles\[0\].shape: got "cone"'),
        (dict(obstacles=[{"shape": "sphere", "center": [0, 0, 0]}]), r"obstacles\[0\]: missing key `radius`"),
        (dict(obstacles=[{"shape": "sphere", "center": [0, 0, 0], "radius": 1, "colour": 1}]), r"obstacles\[0\].colour: no such key"),
        (dict(obstacles=[{"shape": "sphere", "center": [0, 0, 0], "radius": -1.0}]), r"obstacle 0"),
        (dict(obstacles=[{"shape": "plane", "normal": [0, 1]}]), r"obstacles\[0\].normal: expected 3 numbers, got shape \(2,\)"),
        (dict(dt=0.0), r"timing"),
    ],
)
def test_bad_arrays_name_the_argument_and_the_item(change, message):
    with pytest.raises(hooke.SceneError, match=message):
        hooke.Scene.from_arrays(**{**TWO, **change})


def test_bad_scene_files_and_names_give_the_command_lines_message():
    with pytest.raises(hooke.SceneError, match=r"^bad.toml:3: simulation.dt: "):
        hooke.Scene.from_toml("[simulation]\nduration = 1.0\ndt = -0.1\n", "bad.toml")
    with pytest.raises(hooke.SceneError, match='no built-in scene "nope"'):
        hooke.Scene.builtin("nope")
    with pytest.raises(hooke.SceneError, match="cannot read|No such file"):
        hooke.Scene.from_file("/no/such/scene.toml")
    with pytest.raises(hooke.SceneError, match="scene: got 3"):
        hooke.Simulation(3)


def test_bad_integrators_and_keywords_are_named():
    with pytest.raises(hooke.SettingsError, match='integrator: got "dopri5", expected one of'):
        hooke.Simulation("chain", "dopri5")
    with pytest.raises(hooke.SettingsError, match=r"^colour: got `colour`, expected one of"):
        hooke.Simulation("chain", colour="red")
    with pytest.raises(hooke.SettingsError, match="newton_tolerance"):
        hooke.Simulation("chain", newton_tolerance=-1.0)
    with pytest.raises(hooke.SettingsError, match=r'^solver: integrator "rk4" takes no keyword `solver`'):
        hooke.Simulation("chain", "rk4", solver="pcg")
    with pytest.raises(hooke.SettingsError, match="history"):
        hooke.Simulation("chain", history=3)
    with pytest.raises(hooke.SettingsError, match="rtol"):
        hooke.Simulation("chain", "dormand-prince", rtol=-1.0)
    with pytest.raises(hooke.SettingsError, match="solver: got"):
        hooke.Simulation("chain", solver=[1])
    with pytest.raises(hooke.SettingsError, match="methods: no integrator"):
        hooke.stability("oscillator", methods=["nope"])


def test_bad_states_are_refused_and_leave_the_simulation_as_it_was():
    sim = hooke.Simulation("chain", "rk4")
    before = sim.positions
    with pytest.raises(hooke.StateError, match=r"positions: expected an array of shape \(\d+, 3\)"):
        sim.positions = before[:-1]
    bad = before.copy()
    bad[2, 1] = np.inf
    with pytest.raises(hooke.StateError, match="velocities: row 2 is not finite"):
        sim.velocities = bad
    with pytest.raises(hooke.StateError, match="dt: must be positive"):
        sim.dt = -1.0
    with pytest.raises(hooke.StateError, match="t: must be finite"):
        sim.advance(float("nan"))
    assert np.array_equal(sim.positions, before)
    assert sim.step()["steps"] == 1


def test_a_failed_step_raises_and_keeps_the_state():
    # An explicit method cannot keep a self-colliding cloth apart.
    sim = hooke.Simulation("cloth-pile", "rk4")
    before = sim.positions
    with pytest.raises(hooke.StepError, match="surface"):
        sim.step()
    assert np.array_equal(sim.positions, before) and sim.steps == 0
