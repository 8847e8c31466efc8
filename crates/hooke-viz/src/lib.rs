//! Pictures and files of hooke: the software renderer of frames, the PLY
//! and GIF writers, and the lab's figures ([`plot`]) as PNG and SVG.
//!
//! | file | written by | format |
//! | --- | --- | --- |
//! | `frame_00000.ply`, `frame_00001.ply`, ... | [`write_frame`] | binary little-endian PLY, one file per written frame ([`frame_file_name`]) |
//! | `preview.png` | [`Renderer::render`] + [`save_png`] | an RGBA PNG picture of one frame |
//! | `animation.usda` | [`write_usda`] | the frames as one USD animation: each body a mesh (or curves, for ropes) with its points sampled at every frame, the obstacles as their shapes (see [`usd`]) |
//! | `animation.gif` | [`AnimationWriter`] | a looping GIF of the rendered frames, at most [`MAX_GIF_WIDTH`] pixels wide and about [`MAX_GIF_FRAMES`] frames long |
//! | `stability.png`/`.svg`, `work_precision.png`/`.svg`, ... | [`plot`] | the lab's figures: PNG for viewing, SVG (vector) for papers |
//!
//! The bodies of a scene become one [`Mesh`] ([`scene_mesh`]) and its
//! obstacles are drawn as they are in the model, [`hooke_core::Shape`]s
//! moved along their paths ([`obstacles_at`]). Frames written with
//! [`write_ply`] are read back with [`read_ply`], so pictures can be drawn
//! after a run, once it is known where its bodies came to rest.
//!
//! # PLY frames
//!
//! The topology is given once as a [`Mesh`] (vertex count, triangles,
//! edges); each frame then passes only its positions. A frame file is
//! readable by Blender, MeshLab and ParaView. Its header, for a mesh of `N`
//! vertices, `F` triangles and `E` edges, is
//!
//! ```text
//! ply
//! format binary_little_endian 1.0
//! comment written by hooke
//! element vertex N
//! property float x
//! property float y
//! property float z
//! element face F
//! property list uchar int vertex_indices
//! element edge E
//! property int vertex1
//! property int vertex2
//! end_header
//! ```
//!
//! followed by the `N` positions as three little-endian `f32` each, the `F`
//! faces as the byte `3` and three little-endian `i32` indices each, and the
//! `E` edges as two little-endian `i32` indices each. The `face` lines are
//! left out when the mesh has no triangles (ropes, lattices) and the `edge`
//! lines when it has no edges. Positions are rounded from `f64` to `f32`,
//! the precision those tools read.
//!
//! # Pictures
//!
//! The [`Renderer`] draws a frame with a perspective [`Camera`] into a
//! depth-tested, 2 × 2 supersampled canvas: triangles shaded per sample in
//! linear light from normals interpolated between their corners, two-sided
//! with the front ([`Style::body`]) and back ([`Style::body_back`]) of a
//! surface in different colours, under a key light from above and the
//! viewer's left ([`Renderer::light`]) and a sky-and-ground ambient light;
//! edges as thin lines; and the obstacles of the scene
//! ([`hooke_core::Shape`]s): spheres, capsules and boxes shaded like the
//! bodies, and infinite planes as a checkered floor that fades into the
//! background, on which everything else casts a soft shadow (an area light
//! sampled in several directions, then blurred). The camera looks at the
//! centre of a [`Bounds`] from a [`View`] (by default azimuth 35°,
//! elevation 25°, +y up) at the distance where the scene fills 80 % of the
//! shorter image side.
//!
//! ```
//! use hooke_viz::{Bounds, Camera, Mesh, Renderer, View};
//! use hooke_core::Vec3;
//! let mesh = Mesh::new(3, vec![[0, 1, 2]], Vec::new())?;
//! let positions = [Vec3::zeros(), Vec3::x(), Vec3::y()];
//! let bounds = Bounds::of_scene(&positions, &[]).expect("three points");
//! let camera = Camera::new(&bounds, 320, 240, &View::default())?;
//! let picture = Renderer::new(camera).render(&mesh, &positions, &[])?;
//! assert_eq!((picture.width(), picture.height()), (320, 240));
//! # Ok::<(), hooke_viz::OutputError>(())
//! ```
//!
//! # Dependencies
//!
//! `tiny-skia` rasterises pictures and figures and writes PNG, `gif`
//! encodes animations and `font8x8` is the figures' public-domain bitmap
//! font (no system font is looked up). SVG is written by hand, one element
//! per drawing call of the same figure code that draws the PNG, so the two
//! files of a figure cannot disagree; a plotting crate was measured as the
//! alternative (see [`plot`]).
//!
//! # Errors
//!
//! Writers return [`OutputError`]s and the figures [`PlotError`]s; I/O
//! failures name the file concerned, and bad input (indices out of range,
//! non-finite positions, degenerate obstacles) names the offending item.
//! Nothing here panics on user input.

mod animation;
mod backdrop;
mod bounds;
mod camera;
mod error;
mod frame;
mod framing;
mod mesh;
pub mod plot;
mod ply;
mod raster;
mod render;
mod scene_mesh;
mod shadow;
mod shape;
mod style;
mod tessellate;
pub mod usd;

pub use animation::{AnimationWriter, EncodedFrame, MAX_GIF_FRAMES, MAX_GIF_WIDTH};
pub use backdrop::Backdrop;
pub use bounds::Bounds;
pub use camera::{Camera, MAX_IMAGE_SIDE, Projected, View};
pub use error::{OutputError, Primitive};
pub use framing::run_bounds;
pub use mesh::Mesh;
pub use plot::PlotError;
pub use ply::{frame_file_name, read_ply, write_frame, write_ply};
pub use render::{Renderer, save_png};
pub use scene_mesh::{obstacles_at, scene_mesh};
pub use shape::{check_shape, shape_bounds};
pub use style::{Rgb, Style};
pub use tiny_skia::Pixmap;
pub use usd::{AnimationFrame, write_usda};
