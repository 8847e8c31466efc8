"""Shared fixtures: the default scene run once by hooke.run and once by the
command line, and a reader of the PLY frames they write."""

from pathlib import Path

import numpy as np
import pytest

import hooke

#: The keys of a summary that are wall-clock times (or a share of them) or
#: the output folder: everything else is the same for the same run.
TIMING_KEYS = {
    "wall_s",
    "simulation_s",
    "output_s",
    "step_ms_median",
    "step_ms_max",
    "detection_share",
    "out",
}


def read_ply(path):
    """The positions of a PLY frame as hooke writes it: an (n, 3) float32
    array, read independently of hooke."""
    data = Path(path).read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    assert header[:2] == ["ply", "format binary_little_endian 1.0"]
    vertices = next(int(line.split()[2]) for line in header if line.startswith("element vertex"))
    return np.frombuffer(data, dtype="<f4", count=3 * vertices, offset=end).reshape(vertices, 3)


def frames(out):
    """The frame files in a run's folder, in order."""
    return sorted(Path(out).glob("frame_*.ply"))


@pytest.fixture(scope="session")
def default_run(tmp_path_factory):
    """hooke.run of the default scene: its summary and folder."""
    out = tmp_path_factory.mktemp("python-run")
    summary = hooke.run(out=out, gif=False)
    return summary, out


@pytest.fixture(scope="session")
def command_line_run(tmp_path_factory):
    """`hooke run` of the default scene, by the command line: its folder."""
    out = tmp_path_factory.mktemp("command-line-run")
    assert hooke.main(["run", "--out", str(out), "--quiet", "--no-gif"]) == 0
    return out
