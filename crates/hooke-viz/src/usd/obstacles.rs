//! The obstacles of an animation as USD prims: spheres, boxes and capsules
//! as USD's own shapes, a plane as a square mesh, each placed by a
//! translation that follows its path.

use std::f64::consts::PI;
use std::io::Write;

use hooke_core::{Obstacle, Path, Shape, System, Vec3};
use nalgebra::{Rotation3, UnitQuaternion};

use super::AnimationFrame;
use super::text::{Names, point_f64};

/// Half the side of the square drawn for a plane, in units of the run's
/// size: far beyond the bodies, as a floor should be.
const PLANE_HALF_SIDE: f64 = 4.0;

/// Writes every obstacle of `system` as a prim named for its shape.
pub(super) fn write(
    out: &mut impl Write,
    system: &System,
    frames: &[AnimationFrame],
    size: f64,
) -> std::io::Result<()> {
    let mut names = Names::default();
    for obstacle in system.obstacles() {
        let (kind, centre) = match obstacle.shape {
            Shape::Plane { .. } => ("plane", Vec3::zeros()),
            Shape::Sphere { center, .. } => ("sphere", center),
            Shape::Box { center, .. } => ("box", center),
            Shape::Capsule { a, b, .. } => ("capsule", 0.5 * (a + b)),
        };
        let name = names.unique(kind);
        let prim = match obstacle.shape {
            Shape::Plane { .. } => "Mesh",
            Shape::Sphere { .. } => "Sphere",
            Shape::Box { .. } => "Cube",
            Shape::Capsule { .. } => "Capsule",
        };
        writeln!(out, "        def {prim} \"{name}\"\n        {{")?;
        let mut order = vec!["\"xformOp:translate\""];
        match obstacle.shape {
            Shape::Plane { point, normal } => plane(out, point, normal, size)?,
            Shape::Sphere { radius, .. } => {
                writeln!(out, "            double radius = {radius}")?;
                let r = Vec3::repeat(radius);
                extent(out, -r, r)?;
            }
            Shape::Box {
                half_extents,
                rotation,
                ..
            } => {
                writeln!(out, "            double size = 2")?;
                extent(out, -Vec3::repeat(1.0), Vec3::repeat(1.0))?;
                let turn = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(
                    rotation,
                ));
                orient(out, turn)?;
                let scale = point_f64(half_extents);
                writeln!(out, "            double3 xformOp:scale = {scale}")?;
                order.extend(["\"xformOp:orient\"", "\"xformOp:scale\""]);
            }
            Shape::Capsule { a, b, radius } => {
                let axis = b - a;
                let height = axis.norm();
                writeln!(out, "            uniform token axis = \"Z\"")?;
                writeln!(out, "            double height = {height}")?;
                writeln!(out, "            double radius = {radius}")?;
                let r = Vec3::new(radius, radius, radius + 0.5 * height);
                extent(out, -r, r)?;
                let turn = UnitQuaternion::rotation_between(&Vec3::z(), &axis)
                    .unwrap_or_else(|| UnitQuaternion::from_axis_angle(&Vec3::x_axis(), PI));
                orient(out, turn)?;
                order.push("\"xformOp:orient\"");
            }
        }
        translate(out, obstacle, centre, frames)?;
        writeln!(
            out,
            "            uniform token[] xformOpOrder = [{}]\n        }}\n",
            order.join(", ")
        )?;
    }
    Ok(())
}

/// A plane as a square mesh around its point, `2 PLANE_HALF_SIDE · size`
/// on a side, facing along its normal.
fn plane(out: &mut impl Write, point: Vec3, normal: Vec3, size: f64) -> std::io::Result<()> {
    let n = normal.try_normalize(0.0).unwrap_or_else(Vec3::y);
    // Two directions in the plane: the axis least along the normal, made
    // orthogonal to it, and their cross product.
    let least = (0..3)
        .min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
        .map_or_else(Vec3::x, |i| Vec3::ith(i, 1.0));
    let u = (least - least.dot(&n) * n).normalize();
    let v = n.cross(&u);
    let half = PLANE_HALF_SIDE * size;
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(a, b)| point + half * (a * u + b * v));
    writeln!(out, "            uniform bool doubleSided = 1")?;
    writeln!(out, "            int[] faceVertexCounts = [4]")?;
    writeln!(out, "            int[] faceVertexIndices = [0, 1, 2, 3]")?;
    let points = corners.map(point_f64).join(", ");
    writeln!(out, "            point3f[] points = [{points}]")?;
    writeln!(
        out,
        "            uniform token subdivisionScheme = \"none\""
    )?;
    let low = corners.iter().fold(corners[0], |m, c| m.inf(c));
    let high = corners.iter().fold(corners[0], |m, c| m.sup(c));
    extent(out, low, high)
}

fn extent(out: &mut impl Write, low: Vec3, high: Vec3) -> std::io::Result<()> {
    writeln!(
        out,
        "            float3[] extent = [{}, {}]",
        point_f64(low),
        point_f64(high)
    )
}

/// `xformOp:orient`, a quaternion written `(w, x, y, z)`.
fn orient(out: &mut impl Write, turn: UnitQuaternion<f64>) -> std::io::Result<()> {
    let q = turn.quaternion();
    writeln!(
        out,
        "            quatd xformOp:orient = ({}, {}, {}, {})",
        q.w, q.i, q.j, q.k
    )
}

/// `xformOp:translate`: the shape's centre plus its path's offset, one
/// sample per frame for a moving obstacle.
fn translate(
    out: &mut impl Write,
    obstacle: &Obstacle,
    centre: Vec3,
    frames: &[AnimationFrame],
) -> std::io::Result<()> {
    if obstacle.path == Path::Fixed {
        return writeln!(
            out,
            "            double3 xformOp:translate = {}",
            point_f64(centre)
        );
    }
    writeln!(
        out,
        "            double3 xformOp:translate.timeSamples = {{"
    )?;
    for frame in frames {
        let at = centre + obstacle.path.offset(frame.time);
        writeln!(
            out,
            "                {}: {},",
            frame.time_code,
            point_f64(at)
        )?;
    }
    writeln!(out, "            }}")
}
