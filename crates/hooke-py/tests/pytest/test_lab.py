"""stability and accuracy give the command line's cells and runs, as
columns of numpy arrays."""

import json

import numpy as np

import hooke

#: Wall times differ from run to run; everything else is the same.
WALL = {"wall_s"}


def columns(records):
    """JSON records as the package returns them: a dict of columns."""
    return {key: [r[key] for r in records] for key in records[0]}


def assert_same_columns(returned, records):
    expected = columns(records)
    assert set(returned) == set(expected)
    for key, values in expected.items():
        if key in WALL:
            continue
        got = returned[key]
        if isinstance(got, np.ndarray):
            values = np.array([np.nan if v is None else v for v in values], dtype=got.dtype)
            np.testing.assert_array_equal(got, values, err_msg=key)
        else:
            # Names, or lists of numbers as arrays.
            np.testing.assert_equal(list(got), values, err_msg=key)


def test_stability_gives_the_command_lines_cells(tmp_path):
    options = dict(methods=["symplectic-euler", "rk4", "backward-euler"], stiffness="1,100",
                   dt="0.05:0.4:3", duration=2.0, min_steps=10)
    report = hooke.stability("oscillator", **options)
    code = hooke.main(["stability", "--builtin", "oscillator", "--methods",
                       "symplectic-euler,rk4,backward-euler", "--stiffness", "1,100",
                       "--dt", "0.05:0.4:3", "--duration", "2", "--min-steps", "10",
                       "--out", str(tmp_path), "--quiet"])
    assert code == 0
    written = json.loads((tmp_path / "stability.json").read_text())
    assert_same_columns(report["cells"], written["cells"])
    assert isinstance(report["cells"]["stable"], np.ndarray) and report["cells"]["stable"].dtype == bool
    np.testing.assert_array_equal(report["dts"], written["dts"])
    assert report["omega_max"] == written["omega_max"]
    # Symplectic Euler is stable below h ω = 2 and not above.
    cells = report["cells"]
    for method, h_omega, stable in zip(cells["integrator"], cells["h_omega"], cells["stable"]):
        if method == "symplectic-euler" and abs(h_omega - 2) > 0.2:
            assert stable == (h_omega < 2), h_omega


def test_accuracy_gives_the_command_lines_runs(tmp_path):
    report = hooke.accuracy("damped-oscillator", methods=["rk4", "velocity-verlet"],
                            dt="0.01:0.1:3", duration=2.0, repeat=1)
    code = hooke.main(["accuracy", "--builtin", "damped-oscillator", "--methods",
                       "rk4,velocity-verlet", "--dt", "0.01:0.1:3", "--duration", "2",
                       "--repeat", "1", "--out", str(tmp_path), "--quiet"])
    assert code == 0
    written = json.loads((tmp_path / "accuracy.json").read_text())
    assert_same_columns(report["runs"], written["runs"])
    assert_same_columns(report["orders"], written["orders"])
    orders = dict(zip(report["orders"]["integrator"], report["orders"]["observed_order"]))
    assert abs(orders["rk4"] - 4) < 0.3 and abs(orders["velocity-verlet"] - 2) < 0.2
