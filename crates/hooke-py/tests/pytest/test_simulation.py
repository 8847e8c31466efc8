"""Simulation: scenes from arrays and from TOML alike, integrators against
closed forms, state set mid-run, the GIL released and Ctrl-C honoured."""

import _thread
import threading
import time

import numpy as np
import pytest

import hooke

CLOTH = """
[simulation]
duration = 0.5
dt = 0.01

[integrator]
method = "backward-euler"

[world]
gravity = [0.0, -9.81, 0.0]
air_damping = 1e-4

[[bodies]]
type = "cloth"
columns = 6
rows = 5
size = [0.5, 0.4]
plane = "horizontal"
offset = [-0.25, 0.3, -0.2]
density = 0.2
stretch = { stiffness = 2e3, damping = 0.01 }
shear = { stiffness = 200.0 }
bend = { stiffness = 5.0 }
pins = ["top-left"]

[[obstacles]]
shape = "sphere"
center = [0.0, 0.1, 0.0]
radius = 0.1
friction = 0.3
"""


def from_arrays_like(scene):
    """The scene rebuilt from its own arrays."""
    return hooke.Scene.from_arrays(
        scene.positions,
        scene.masses,
        scene.springs,
        scene.stiffness,
        scene.rest_lengths,
        scene.damping,
        velocities=scene.velocities,
        pins=scene.pins,
        triangles=scene.triangles,
        gravity=scene.gravity,
        air_damping=scene.air_damping or 0.0,
        obstacles=scene.obstacles,
        dt=scene.dt,
        duration=scene.duration,
    )


def test_a_system_from_arrays_is_the_same_system_as_from_toml():
    toml = hooke.Scene.from_toml(CLOTH, "cloth.toml")
    arrays = from_arrays_like(toml)
    for name in ["positions", "velocities", "masses", "springs", "stiffness", "rest_lengths",
                 "damping", "pins", "triangles"]:
        assert np.array_equal(getattr(toml, name), getattr(arrays, name)), name
    assert arrays.obstacles == toml.obstacles
    assert (arrays.gravity, arrays.air_damping, arrays.contact_distance) == (
        toml.gravity, toml.air_damping, toml.contact_distance)
    a, b = hooke.Simulation(toml), hooke.Simulation(arrays)
    a.advance(0.3)
    b.advance(0.3)
    assert a.report["contacts"] > 0, "the cloth reached the sphere"
    assert np.array_equal(a.positions, b.positions) and np.array_equal(a.velocities, b.velocities)


def test_the_report_prices_collision_detection_under_either_contact_limit():
    for limit in ["global", "particles"]:
        sim = hooke.Simulation("cloth-on-sphere", contact_limit=limit)
        sim.advance(0.3)
        r = sim.report
        assert sim.settings["contact_limit"] == limit
        assert r["contacts"] > 0 and r["proximity_queries"] > 0, limit
        assert 0.0 < r["detection_s"] < r["wall_s"], limit
        assert r["truncated_particles_max"] <= r["truncated_particles"], limit
        assert r["truncated_particles_max"] <= sim.positions.shape[0], limit
        if limit == "global":
            assert r["truncated_particles"] == r["bound_fallbacks"] == 0


WINDY = """
[simulation]
duration = 1.0
dt = 0.01

[integrator]
method = "backward-euler"

[world]
gravity = [0.0, 0.0, 0.0]
wind = { velocity = [0.0, 1.5, 0.0], drag = 0.4 }

[[bodies]]
type = "cloth"
columns = 6
rows = 6
density = 0.2
stretch = { stiffness = 2e3 }
shear = { stiffness = 200.0 }
self_collision = false
"""


def test_a_scene_files_wind_blows_a_free_cloth_along():
    """A free horizontal sheet of ρ kg/m² in a wind W normal to it, without
    gravity, obeys ρ v' = c (W − v); backward Euler's steps of h give
    v_k = W (1 − (1 + h c/ρ)^(−k)). Its corners, with less mass than their
    share of the drag, bend it slightly: the mean velocity follows to 1 %."""
    simulation = hooke.Simulation(hooke.Scene.from_toml(WINDY, "windy.toml"))
    simulation.advance(0.5)
    masses = simulation.scene.masses
    mean = (masses * simulation.velocities[:, 1]).sum() / masses.sum()
    expected = 1.5 * (1.0 - (1.0 + 0.01 * 0.4 / 0.2) ** -simulation.steps)
    assert mean == pytest.approx(expected, rel=1e-2)


def oscillator(omega, amplitude, integrator, dt):
    """A bob of 1 kg on a zero-length spring to a pinned anchor, no
    gravity, released at rest `amplitude` from it: x(t) = A cos ωt."""
    scene = hooke.Scene.from_arrays(
        positions=[[0.0, 0.0, 0.0], [amplitude, 0.0, 0.0]],
        masses=[1.0, 1.0],
        springs=[[0, 1]],
        stiffness=omega**2,
        rest_lengths=0.0,
        pins=[0],
        gravity=(0.0, 0.0, 0.0),
    )
    return hooke.Simulation(scene, integrator, dt=dt)


@pytest.mark.parametrize("integrator", ["velocity-verlet", "leapfrog"])
def test_verlet_oscillator_errs_by_its_phase_error(integrator):
    # Second order, symplectic: the amplitude is kept, the phase lags by
    # θ³/24 a step (θ = hω), so at time T the error is A ω³ T h² / 24.
    omega, amplitude, dt, t_end = 2.0, 0.1, 0.01, 5.0
    sim = oscillator(omega, amplitude, integrator, dt)
    sim.advance(t_end)
    x = sim.positions[1, 0]
    error = abs(x - amplitude * np.cos(omega * sim.time))
    phase = omega**3 * sim.time * dt**2 / 24
    bound = amplitude * phase * abs(np.sin(omega * sim.time))
    assert 0.5 * bound < error < 1.5 * bound


def test_rk4_oscillator_is_fourth_order():
    errors = []
    for dt in [0.04, 0.02]:
        sim = oscillator(1.0, 1.0, "rk4", dt)
        sim.advance(4.0)
        errors.append(abs(sim.positions[1, 0] - np.cos(sim.time)))
    assert errors[0] / errors[1] == pytest.approx(16, rel=0.05)


def test_backward_euler_oscillator_loses_energy_as_its_amplification_factor_says():
    # |R|² = 1 / (1 + θ²) a step, exactly, for the linear oscillator.
    omega, dt, n = 3.0, 0.05, 40
    sim = oscillator(omega, 0.2, "backward-euler", dt)
    start = sim.energy()["total"]
    sim.advance(n * dt)
    assert sim.steps == n
    expected = start * (1 + (omega * dt) ** 2) ** -n
    assert sim.energy()["total"] == pytest.approx(expected, rel=1e-9)


def test_positions_velocities_and_time_set_mid_run_are_honoured():
    fresh = hooke.Simulation("swinging-rope", "leapfrog")
    for _ in range(20):
        fresh.step()
    moved = hooke.Simulation("swinging-rope", "leapfrog")
    moved.advance(0.3)
    # Back to the start by hand: the integrator restarts from that state.
    scene = moved.scene
    moved.positions, moved.velocities, moved.time = scene.positions, scene.velocities, 0.0
    for _ in range(20):
        moved.step()
    assert np.array_equal(moved.positions, fresh.positions)
    assert np.array_equal(moved.velocities, fresh.velocities)
    # A free particle set moving goes where its velocity takes it.
    free = hooke.Simulation(hooke.Scene.from_arrays([[0.0, 0.0, 0.0]], 1.0, gravity=(0, 0, 0)),
                            "symplectic-euler", dt=0.1)
    free.velocities = [[1.0, 2.0, 3.0]]
    free.advance(1.0)
    assert free.positions == pytest.approx(np.array([[1.0, 2.0, 3.0]]))


def test_every_integrator_of_the_scene_format_steps():
    for name in ["explicit-euler", "symplectic-euler", "leapfrog", "velocity-verlet",
                 "position-verlet", "midpoint", "heun", "rk4", "beeman", "gear",
                 "dormand-prince", "backward-euler", "bdf2", "fast-mass-spring"]:
        sim = hooke.Simulation("chain", name)
        report = sim.step()
        assert sim.integrator == name and report["steps"] == 1 and sim.steps == 1, name


def test_keyword_settings_reach_the_integrator():
    sim = hooke.Simulation("chain", solver="pcg", tolerance=1e-9, newton_tolerance=1e-6)
    assert sim.settings["solver"] == "pcg" and sim.settings["tolerance"] == 1e-9
    assert sim.settings["newton_tolerance"] == 1e-6
    assert sim.step()["linear_solver"] == "pcg"
    quasi = hooke.Simulation("chain", step="quasi-newton", history=3)
    assert quasi.settings["history"] == 3 and quasi.settings["weak_springs"] == "routed"
    assert hooke.Simulation("chain", "dormand-prince", rtol=1e-4).settings["rtol"] == 1e-4
    assert hooke.Simulation("chain", "fast-mass-spring", iterations=7).settings == {"iterations": 7}


def test_a_step_runs_without_the_gil():
    sim = hooke.Simulation("stiff-cloth")
    inside = []
    started, finished = [], []

    def work():
        started.append(time.perf_counter())
        sim.advance(0.2)
        finished.append(time.perf_counter())

    worker = threading.Thread(target=work)
    worker.start()
    while worker.is_alive():
        inside.append(time.perf_counter())
    worker.join()
    during = [t for t in inside if started[0] < t < finished[0]]
    assert finished[0] - started[0] > 0.05
    # The main thread kept running through the steps, not only between them.
    assert len(during) > 1000


def test_ctrl_c_stops_a_long_advance_between_steps():
    sim = hooke.Simulation("oscillator", "rk4", dt=1e-4)
    timer = threading.Timer(0.3, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        sim.advance(1e6)
    timer.join()
    assert 0 < sim.steps < 1e10
    assert sim.time == pytest.approx(sim.steps * 1e-4, rel=1e-9)


def test_ctrl_c_stops_a_run(tmp_path):
    scene = hooke.Scene.builtin("oscillator")
    scene.dt = 1e-4
    timer = threading.Timer(0.3, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        hooke.run(scene, tmp_path, gif=False, usd=False, duration=1e4)
    timer.join()
