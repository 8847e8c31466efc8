//! Obstacles as flat triangles for the renderer.
//!
//! Spheres and capsules are surfaces of revolution (a profile of
//! [`RINGS`] latitude steps revolved in [`SEGMENTS`] longitude steps), boxes
//! are six faces of two triangles, and an infinite plane is a square of
//! [`TILES`] x [`TILES`] checkered tiles centred under the framed scene.
//! Normals of closed shapes point outwards, so the renderer can drop the
//! faces turned away from the eye; the corners of spheres and capsules
//! carry the surface's own normal, so they shade smoothly.
//!
//! Each shape is drawn a little inside its surface ([`INSET`] of its radius
//! or half extent; a plane [`PLANE_INSET`] of the framed radius below
//! itself), so that a body resting on it — whose particles the contact
//! response keeps exactly on the surface — is drawn in front of it rather
//! than fighting it for the same depth.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use hooke_core::Vec3;

use hooke_core::Shape;

/// Longitude steps of a sphere or capsule.
const SEGMENTS: usize = 48;
/// Latitude steps of a sphere, pole to pole; a capsule's caps take half each.
const RINGS: usize = 24;
/// Tiles along each side of a plane's square.
const TILES: i64 = 48;
/// Side of a plane's tile, in framed radii.
const TILE: f64 = 1.0 / 3.0;
/// How far inside its surface a sphere, capsule or box is drawn, as a
/// fraction of its radius or half extents: more than the sagitta of a
/// body's facets lying on a sphere of [`SEGMENTS`] steps.
const INSET: f64 = 0.006;
/// How far below itself a plane is drawn, in framed radii.
const PLANE_INSET: f64 = 0.004;

/// What colour a facet takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Tone {
    /// A body of the simulation.
    Body,
    /// A sphere, box or capsule.
    Obstacle,
    /// A light or a dark floor tile.
    Tile(bool),
}

/// A flat triangle with its unit normal and the surface normals at its
/// corners (the flat normal on flat shapes).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Facet {
    pub corners: [Vec3; 3],
    pub normal: Vec3,
    pub corner_normals: [Vec3; 3],
    pub tone: Tone,
    /// Whether it is seen from both sides (open surfaces) or only from the
    /// side its normal points to (closed shapes).
    pub two_sided: bool,
}

impl Facet {
    /// The facet with corners `corners`, or `None` if they are collinear.
    /// For closed shapes the normal is turned away from `inside`.
    pub fn new(corners: [Vec3; 3], tone: Tone, inside: Option<Vec3>) -> Option<Self> {
        let [a, b, c] = corners;
        let cross = (b - a).cross(&(c - a));
        let scale = (b - a).norm_squared().max((c - a).norm_squared());
        if cross.norm_squared() <= 1e-24 * scale * scale || !cross.iter().all(|x| x.is_finite()) {
            return None;
        }
        let mut normal = cross.normalize();
        if let Some(inside) = inside {
            if normal.dot(&((a + b + c) / 3.0 - inside)) < 0.0 {
                normal = -normal;
            }
        }
        Some(Self {
            corners,
            normal,
            corner_normals: [normal; 3],
            tone,
            two_sided: inside.is_none(),
        })
    }

    /// The same facet with the surface normals `normals` at its corners.
    pub fn smooth(self, normals: [Vec3; 3]) -> Self {
        Self {
            corner_normals: normals,
            ..self
        }
    }
}

/// Appends the facets of `shape` to `out`. A plane is drawn as a square of
/// [`TILES`]² tiles of side [`TILE`]` reach` centred on the projection of
/// `focus` onto it.
pub(crate) fn tessellate(shape: &Shape, focus: Vec3, reach: f64, out: &mut Vec<Facet>) {
    match *shape {
        Shape::Sphere { center, radius } => {
            let radius = radius * (1.0 - INSET);
            let profile: Vec<(f64, f64)> = (0..=RINGS)
                .map(|i| latitude(-FRAC_PI_2 + PI * i as f64 / RINGS as f64, radius, 0.0))
                .collect();
            revolve(center, Vec3::y(), 0.0, &profile, out);
        }
        Shape::Capsule { a, b, radius } => {
            let radius = radius * (1.0 - INSET);
            let length = (b - a).norm();
            let axis = if length > 0.0 {
                (b - a) / length
            } else {
                Vec3::y()
            };
            let half = RINGS / 2;
            let step = FRAC_PI_2 / half as f64;
            let profile: Vec<(f64, f64)> = (0..=half)
                .map(|i| latitude(-FRAC_PI_2 + step * i as f64, radius, 0.0))
                .chain((0..=half).map(|i| latitude(step * i as f64, radius, length)))
                .collect();
            revolve(a, axis, length, &profile, out);
        }
        Shape::Box {
            center,
            half_extents,
            rotation,
        } => {
            let axes: [Vec3; 3] = std::array::from_fn(|i| {
                rotation.column(i).into_owned() * half_extents[i] * (1.0 - INSET)
            });
            for i in 0..3 {
                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                for side in [-1.0, 1.0] {
                    let mid = center + axes[i] * side;
                    let quad = [
                        mid - axes[j] - axes[k],
                        mid + axes[j] - axes[k],
                        mid + axes[j] + axes[k],
                        mid - axes[j] + axes[k],
                    ];
                    push_quad(quad, Tone::Obstacle, Some(center), out);
                }
            }
        }
        Shape::Plane { point, normal } => {
            let normal = normal.normalize();
            plane(
                point - normal * (PLANE_INSET * reach),
                normal,
                focus,
                reach,
                out,
            );
        }
    }
}

/// A profile point at latitude `phi` on a circle of `radius` whose centre
/// sits `offset` along the axis: `(axial, radial)`.
fn latitude(phi: f64, radius: f64, offset: f64) -> (f64, f64) {
    (offset + radius * phi.sin(), radius * phi.cos())
}

/// Revolves `profile` (axial, radial) about the axis through `origin` along
/// unit `axis`; the solid's core is the axis segment of length `length`.
fn revolve(origin: Vec3, axis: Vec3, length: f64, profile: &[(f64, f64)], out: &mut Vec<Facet>) {
    let (u, v) = basis(axis);
    let ring = |(axial, radial): (f64, f64)| -> Vec<Vec3> {
        (0..SEGMENTS)
            .map(|k| {
                let theta = TAU * k as f64 / SEGMENTS as f64;
                origin + axis * axial + (u * theta.cos() + v * theta.sin()) * radial
            })
            .collect()
    };
    let rings: Vec<Vec<Vec3>> = profile.iter().map(|&p| ring(p)).collect();
    for (low, high) in rings.iter().zip(&rings[1..]) {
        for k in 0..SEGMENTS {
            let next = (k + 1) % SEGMENTS;
            let quad = [low[k], low[next], high[next], high[k]];
            let core = |p: Vec3| origin + axis * (p - origin).dot(&axis).clamp(0.0, length);
            let centroid = quad.iter().sum::<Vec3>() / 4.0;
            let [a, b, c, d] = quad;
            let outward = |p: Vec3| (p - core(p)).try_normalize(0.0).unwrap_or(axis);
            let inside = Some(core(centroid));
            for corners in [[a, b, c], [a, c, d]] {
                out.extend(
                    Facet::new(corners, Tone::Obstacle, inside)
                        .map(|f| f.smooth(corners.map(outward))),
                );
            }
        }
    }
}

/// The checkered square of a plane through `point` with unit `normal`.
/// Tiles are anchored to the plane, so they stay put as the framing moves.
fn plane(point: Vec3, normal: Vec3, focus: Vec3, reach: f64, out: &mut Vec<Facet>) {
    let (u, v) = basis(normal);
    let tile = TILE * reach;
    let foot = focus - normal * (focus - point).dot(&normal);
    // Clamped so that absurd scales cannot overflow the tile indices.
    let first =
        |dir: Vec3| ((foot - point).dot(&dir) / tile).round().clamp(-1e15, 1e15) as i64 - TILES / 2;
    let (iu, iv) = (first(u), first(v));
    for a in iu..iu + TILES {
        for b in iv..iv + TILES {
            let corner = |da: i64, db: i64| {
                point + u * ((a + da) as f64 * tile) + v * ((b + db) as f64 * tile)
            };
            let quad = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
            push_quad(quad, Tone::Tile((a + b).rem_euclid(2) == 0), None, out);
        }
    }
}

fn push_quad(quad: [Vec3; 4], tone: Tone, inside: Option<Vec3>, out: &mut Vec<Facet>) {
    let [a, b, c, d] = quad;
    out.extend(Facet::new([a, b, c], tone, inside));
    out.extend(Facet::new([a, c, d], tone, inside));
}

/// Two unit vectors completing unit `n` to an orthonormal basis.
pub(crate) fn basis(n: Vec3) -> (Vec3, Vec3) {
    let helper = if n.x.abs() < 0.9 {
        Vec3::x()
    } else {
        Vec3::z()
    };
    let u = n.cross(&helper).normalize();
    (u, n.cross(&u))
}

#[cfg(test)]
mod tests {
    use nalgebra::Rotation3;

    use super::*;

    fn facets(shape: &Shape) -> Vec<Facet> {
        let mut out = Vec::new();
        tessellate(shape, Vec3::zeros(), 1.0, &mut out);
        out
    }

    #[test]
    fn closed_shapes_have_outward_normals() {
        let shapes = [
            Shape::Sphere {
                center: Vec3::new(1.0, 2.0, 3.0),
                radius: 0.5,
            },
            Shape::Capsule {
                a: Vec3::zeros(),
                b: Vec3::new(1.0, 1.0, 0.0),
                radius: 0.2,
            },
            Shape::Box {
                center: Vec3::x(),
                half_extents: Vec3::new(1.0, 0.5, 0.25),
                rotation: Rotation3::from_euler_angles(0.1, 0.2, 0.3).into_inner(),
            },
        ];
        for shape in &shapes {
            let bounds = crate::shape_bounds(shape).unwrap();
            let facets = facets(shape);
            assert!(!facets.is_empty());
            for f in &facets {
                assert!(!f.two_sided);
                let centroid = f.corners.iter().sum::<Vec3>() / 3.0;
                assert!(
                    f.normal.dot(&(centroid - bounds.center())) > 0.0,
                    "{shape:?}"
                );
            }
        }
    }

    #[test]
    fn plane_is_a_checkered_square_in_the_plane() {
        let plane = Shape::Plane {
            point: Vec3::new(0.0, -1.0, 0.0),
            normal: Vec3::new(0.0, 2.0, 0.0),
        };
        let facets = facets(&plane);
        assert_eq!(facets.len(), (2 * TILES * TILES) as usize);
        let light = facets.iter().filter(|f| f.tone == Tone::Tile(true)).count();
        assert_eq!(light, facets.len() / 2);
        for f in &facets {
            assert!(f.two_sided);
            // Drawn just below the plane, so what rests on it stays in front.
            assert!(
                f.corners
                    .iter()
                    .all(|c| (c.y + 1.0 + PLANE_INSET).abs() < 1e-12)
            );
        }
    }
}
