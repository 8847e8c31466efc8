"""animation.usda as Pixar's own USD library reads it: the stage's time
range and units, one time sample per written frame holding that frame's
points, and the default scene's sphere and floor."""

import numpy as np
import pytest

from conftest import frames, read_ply

from pxr import Usd, UsdGeom


@pytest.fixture(scope="module")
def stage(default_run):
    _, out = default_run
    return Usd.Stage.Open(str(out / "animation.usda"))


def test_the_stage_spans_the_frames_at_the_frame_rate(default_run, stage):
    summary, _ = default_run
    assert stage.GetStartTimeCode() == 0
    assert stage.GetEndTimeCode() == summary["frames"] - 1
    assert stage.GetTimeCodesPerSecond() == 60
    assert UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.y
    assert UsdGeom.GetStageMetersPerUnit(stage) == 1
    assert stage.GetDefaultPrim().GetPath() == "/World"


def test_the_cloth_is_a_mesh_sampled_at_every_frame(default_run, stage):
    _, out = default_run
    cloth = UsdGeom.Mesh(stage.GetPrimAtPath("/World/bodies/cloth"))
    assert cloth
    points = cloth.GetPointsAttr()
    written = frames(out)
    assert points.GetTimeSamples() == list(range(len(written)))
    for k, frame in enumerate(written):
        assert np.array_equal(np.array(points.Get(k), dtype=np.float32), read_ply(frame)), k
    counts = np.array(cloth.GetFaceVertexCountsAttr().Get())
    indices = np.array(cloth.GetFaceVertexIndicesAttr().Get()).reshape(-1, 3)
    assert (counts == 3).all() and len(indices) == 2 * 39 * 39
    assert indices.max() == 1599


def test_the_sphere_and_the_floor_are_prims(stage):
    sphere = UsdGeom.Sphere(stage.GetPrimAtPath("/World/obstacles/sphere"))
    assert sphere.GetRadiusAttr().Get() == pytest.approx(0.18)
    translate = UsdGeom.Xformable(sphere).ComputeLocalToWorldTransform(0).ExtractTranslation()
    assert tuple(translate) == pytest.approx((0.0, 0.18, 0.0))
    floor = UsdGeom.Mesh(stage.GetPrimAtPath("/World/obstacles/plane"))
    corners = np.array(floor.GetPointsAttr().Get())
    assert corners.shape == (4, 3) and (corners[:, 1] == 0).all()
    # Far wider than the cloth, which lies within a metre of the origin.
    assert np.abs(corners[:, [0, 2]]).min() > 1.0
