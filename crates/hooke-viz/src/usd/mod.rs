//! A run as one USD animation (`animation.usda`, the text form of Pixar's
//! Universal Scene Description), which Blender, Houdini and usdview open as
//! a single animated scene, where the PLY frames are one file each.
//!
//! The file is written here, by hand, as the PLY frames are: the subset
//! of USD it uses is small and stable, and a USD library would bring a
//! C++ build into every build of hooke. Its layout, for a scene with a
//! cloth, a rope, a sphere and a floor:
//!
//! ```text
//! #usda 1.0
//! (
//!     defaultPrim = "World"
//!     startTimeCode = 0
//!     endTimeCode = 210            # the last frame's time code
//!     timeCodesPerSecond = 60      # frames per simulated second
//!     framesPerSecond = 60
//!     upAxis = "Y"                 # "Z" when gravity points along −z
//!     metersPerUnit = 1
//! )
//! def Xform "World" {
//!     def Scope "bodies" {
//!         def Mesh "cloth" { faceVertexCounts, faceVertexIndices,
//!                            points.timeSamples, extent.timeSamples }
//!         def BasisCurves "rope" { type = "linear", curveVertexCounts,
//!                                  points.timeSamples, widths }
//!     }
//!     def Scope "obstacles" {
//!         def Sphere "sphere" { radius, xformOp:translate }
//!         def Mesh "plane" { a square of the plane, 4 × the scene's size }
//!     }
//! }
//! ```
//!
//! Every body of the scene is one prim under `bodies`, named for the body
//! (made a valid USD identifier, `_2`, `_3` … for repeats), with its own
//! particles as points: a body with triangles is a `Mesh` of them, a body
//! with segments (a rope) a `BasisCurves` of linear curves through them, a
//! body with neither a `Points` prim. Its points are sampled at every
//! written frame, `time code = (steps taken) / (steps per frame)`, so the
//! frames fall on whole time codes and a last frame off that grid between
//! two. Points are single precision, as in the PLY frames, and written with
//! the shortest decimals that read back to the same `f32`: the animation
//! holds exactly the frames' values. Obstacles are their shapes — a
//! `Sphere`, a `Cube` scaled to the box and turned by `xformOp:orient`, a
//! `Capsule` along its axis, a plane as a square `Mesh` — placed by
//! `xformOp:translate`, time-sampled at the frames for moving ones.

mod obstacles;
mod text;

use std::fs::File;
use std::io::{BufWriter, Write};
use std::ops::Range;
use std::path::Path;

use hooke_core::Vec3;
use hooke_scenes::{Scene, SceneBody};

use crate::error::{OutputError, Primitive};
use crate::framing::run_bounds;
use text::{Names, point};

/// A written frame as the animation places it in time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AnimationFrame {
    /// Its USD time code: steps taken over steps per frame.
    pub time_code: f64,
    /// The simulated time, s.
    pub time: f64,
}

/// Writes `scene`'s bodies at `frames` and its obstacles to `path` as a
/// USD text file (see the [module docs](self)). `time_codes_per_second` is
/// the frames per simulated second; `positions(k)` gives frame `k`'s
/// particle positions, e.g. read back from its PLY file ([`crate::read_ply`]).
///
/// ```
/// use hooke_viz::{AnimationFrame, write_usda};
/// let scene = hooke_scenes::builtin::load("chain")?;
/// let x = scene.system.initial_positions().to_vec();
/// let frames = [0.0, 1.0].map(|k| AnimationFrame { time_code: k, time: k / 60.0 });
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("animation.usda");
/// write_usda(&path, &scene, &frames, 60.0, &mut |_| Ok(x.clone()))?;
/// let text = std::fs::read_to_string(&path)?;
/// assert!(text.starts_with("#usda 1.0"));
/// assert!(text.contains("endTimeCode = 1\n"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`OutputError::EmptyAnimation`] without frames;
/// [`OutputError::FrameRate`] for a rate that is not positive and finite;
/// [`OutputError::PositionCount`] for a frame with fewer positions than
/// the bodies place, [`OutputError::VertexOutOfRange`] for a body's
/// triangle or segment outside its own particles; any error of
/// `positions`; [`OutputError::Create`] or [`OutputError::Write`] naming
/// `path`.
pub fn write_usda(
    path: &Path,
    scene: &Scene,
    frames: &[AnimationFrame],
    time_codes_per_second: f64,
    positions: &mut dyn FnMut(usize) -> Result<Vec<Vec3>, OutputError>,
) -> Result<(), OutputError> {
    let (Some(first), Some(last)) = (frames.first(), frames.last()) else {
        return Err(OutputError::EmptyAnimation {
            path: path.to_path_buf(),
        });
    };
    if !(time_codes_per_second.is_finite() && time_codes_per_second > 0.0) {
        return Err(OutputError::FrameRate {
            fps: time_codes_per_second,
        });
    }
    let bodies = scene
        .bodies
        .iter()
        .map(BodyPrim::new)
        .collect::<Result<Vec<_>, _>>()?;
    let file = File::create(path).map_err(|source| OutputError::Create {
        path: path.to_path_buf(),
        source,
    })?;
    let mut out = BufWriter::new(file);
    let size = run_bounds(&scene.system, last.time).map_or(1.0, |b| b.radius());
    let stage = Stage {
        scene,
        frames,
        start: first.time_code,
        end: last.time_code,
        rate: time_codes_per_second,
        size,
    };
    let written = stage
        .write(&mut out, &bodies, positions)
        .and_then(|()| out.flush().map_err(Failure::Io));
    written.map_err(|failure| match failure {
        Failure::Io(source) => OutputError::Write {
            path: path.to_path_buf(),
            source,
        },
        Failure::Output(error) => error,
    })
}

/// Why writing stopped: the file, or the frames.
enum Failure {
    Io(std::io::Error),
    Output(OutputError),
}

impl From<std::io::Error> for Failure {
    fn from(error: std::io::Error) -> Self {
        Self::Io(error)
    }
}

/// What the whole file is written from.
struct Stage<'a> {
    scene: &'a Scene,
    frames: &'a [AnimationFrame],
    start: f64,
    end: f64,
    rate: f64,
    /// The radius of the run's bounds, m: the scale of curve widths and of
    /// the square drawn for a plane.
    size: f64,
}

impl Stage<'_> {
    fn write(
        &self,
        out: &mut impl Write,
        bodies: &[BodyPrim],
        positions: &mut dyn FnMut(usize) -> Result<Vec<Vec3>, OutputError>,
    ) -> Result<(), Failure> {
        let up = match self.scene.system.gravity() {
            Some(g) if g.z.abs() > g.x.abs().max(g.y.abs()) => "Z",
            _ => "Y",
        };
        writeln!(out, "#usda 1.0\n(")?;
        writeln!(out, "    defaultPrim = \"World\"")?;
        writeln!(
            out,
            "    doc = \"{}: {} frames, written by hooke\"",
            text::escaped(&self.scene.name),
            self.frames.len()
        )?;
        writeln!(out, "    startTimeCode = {}", self.start)?;
        writeln!(out, "    endTimeCode = {}", self.end)?;
        writeln!(out, "    timeCodesPerSecond = {}", self.rate)?;
        writeln!(out, "    framesPerSecond = {}", self.rate)?;
        writeln!(out, "    upAxis = \"{up}\"\n    metersPerUnit = 1\n)\n")?;
        writeln!(
            out,
            "def Xform \"World\"\n{{\n    def Scope \"bodies\"\n    {{"
        )?;
        let mut names = Names::default();
        for body in bodies {
            self.body(out, body, &names.unique(&body.name), positions)?;
        }
        writeln!(out, "    }}\n\n    def Scope \"obstacles\"\n    {{")?;
        obstacles::write(out, &self.scene.system, self.frames, self.size)?;
        writeln!(out, "    }}\n}}")?;
        Ok(())
    }

    /// One body's prim, its points sampled at every frame.
    fn body(
        &self,
        out: &mut impl Write,
        body: &BodyPrim,
        name: &str,
        positions: &mut dyn FnMut(usize) -> Result<Vec<Vec3>, OutputError>,
    ) -> Result<(), Failure> {
        let kind = match &body.shape {
            BodyShape::Mesh(_) => "Mesh",
            BodyShape::Curves(_) => "BasisCurves",
            BodyShape::Points => "Points",
        };
        writeln!(out, "        def {kind} \"{name}\"\n        {{")?;
        let width = 2e-3 * self.size;
        match &body.shape {
            BodyShape::Mesh(triangles) => {
                writeln!(out, "            uniform bool doubleSided = 1")?;
                let counts = vec!["3"; triangles.len()].join(", ");
                writeln!(out, "            int[] faceVertexCounts = [{counts}]")?;
                let indices = triangles.iter().flatten().map(ToString::to_string);
                let indices = indices.collect::<Vec<_>>().join(", ");
                writeln!(out, "            int[] faceVertexIndices = [{indices}]")?;
                writeln!(
                    out,
                    "            uniform token subdivisionScheme = \"none\""
                )?;
            }
            BodyShape::Curves(curves) => {
                writeln!(out, "            uniform token type = \"linear\"")?;
                let counts = curves.iter().map(|c| c.len().to_string());
                let counts = counts.collect::<Vec<_>>().join(", ");
                writeln!(out, "            int[] curveVertexCounts = [{counts}]")?;
                writeln!(
                    out,
                    "            float[] widths = [{width}] (interpolation = \"constant\")"
                )?;
            }
            BodyShape::Points => writeln!(
                out,
                "            float[] widths = [{width}] (interpolation = \"constant\")"
            )?,
        }
        let mut extents = Vec::with_capacity(self.frames.len());
        writeln!(out, "            point3f[] points.timeSamples = {{")?;
        for (k, frame) in self.frames.iter().enumerate() {
            let all = positions(k).map_err(Failure::Output)?;
            let points = body.points(&all).map_err(Failure::Output)?;
            write!(out, "                {}: [", frame.time_code)?;
            for (i, p) in points.iter().enumerate() {
                let separator = if i == 0 { "" } else { ", " };
                write!(out, "{separator}{}", point(*p))?;
            }
            writeln!(out, "],")?;
            extents.push(text::extent(&points));
        }
        writeln!(out, "            }}")?;
        writeln!(out, "            float3[] extent.timeSamples = {{")?;
        for (frame, [low, high]) in self.frames.iter().zip(extents) {
            writeln!(
                out,
                "                {}: [{}, {}],",
                frame.time_code,
                point(low),
                point(high)
            )?;
        }
        writeln!(out, "            }}\n        }}\n")?;
        Ok(())
    }
}

/// A body as a prim: its particles and how they are joined.
struct BodyPrim {
    name: String,
    particles: Range<usize>,
    shape: BodyShape,
}

/// How a body's points are joined, in indices into its own particles.
enum BodyShape {
    /// Triangles.
    Mesh(Vec<[usize; 3]>),
    /// Linear curves, each the list of its vertices.
    Curves(Vec<Vec<usize>>),
    /// Nothing: points alone.
    Points,
}

impl BodyPrim {
    /// `body`'s prim; its triangles or, without any, its segments joined
    /// into polylines where one ends where the next begins.
    fn new(body: &SceneBody) -> Result<Self, OutputError> {
        let particles = body.placement.range();
        let local = |primitive, index, i: usize| {
            i.checked_sub(particles.start)
                .filter(|&l| l < particles.len())
                .ok_or(OutputError::VertexOutOfRange {
                    primitive,
                    index,
                    vertex: u32::try_from(i).unwrap_or(u32::MAX),
                    vertices: particles.len(),
                })
        };
        let shape = if !body.triangles.is_empty() {
            let mut triangles = Vec::with_capacity(body.triangles.len());
            for (index, t) in body.triangles.iter().enumerate() {
                let [a, b, c] = t.map(|i| local(Primitive::Triangle, index, i));
                triangles.push([a?, b?, c?]);
            }
            BodyShape::Mesh(triangles)
        } else if !body.segments.is_empty() {
            let mut curves: Vec<Vec<usize>> = Vec::new();
            for (index, s) in body.segments.iter().enumerate() {
                let [a, b] = s.map(|i| local(Primitive::Edge, index, i));
                let (a, b) = (a?, b?);
                match curves.last_mut() {
                    Some(curve) if curve.last() == Some(&a) => curve.push(b),
                    _ => curves.push(vec![a, b]),
                }
            }
            BodyShape::Curves(curves)
        } else {
            BodyShape::Points
        };
        Ok(Self {
            name: body.name.clone(),
            particles,
            shape,
        })
    }

    /// The prim's points in a frame of every particle: the body's own
    /// particles, or for curves each curve's vertices in turn.
    fn points(&self, all: &[Vec3]) -> Result<Vec<Vec3>, OutputError> {
        let own = all
            .get(self.particles.clone())
            .ok_or(OutputError::PositionCount {
                expected: self.particles.end,
                found: all.len(),
            })?;
        Ok(match &self.shape {
            BodyShape::Curves(curves) => curves.iter().flatten().map(|&i| own[i]).collect(),
            BodyShape::Mesh(_) | BodyShape::Points => own.to_vec(),
        })
    }
}
