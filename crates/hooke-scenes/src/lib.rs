//! Scene builders for hooke: cloth, ropes, box lattices, tetrahedral meshes
//! and layered models, and the mesh files they can start from.
//!
//! Every builder is a consuming builder whose `build()` validates the whole
//! description and returns a [`Body`]: particles (mass, position), springs
//! (ends, stiffness, rest length, damping and [`Family`]), volume elements
//! (tets, for the volumetric bodies), pins, and the surface triangles (or,
//! for a rope, the segments) to draw. A body goes into
//! a [`hooke_core::SystemBuilder`] with [`Body::add_to`], beside any other
//! bodies, or becomes a system alone with [`Body::system`]. Rest lengths are
//! the distances in the initial shape, so every body starts at rest.
//!
//! ```
//! use hooke_scenes::{Cloth, Corner, Springs};
//! let system = Cloth::grid(40, 40)
//!     .size(1.0, 1.0)
//!     .stretch(Springs::per_spring(5e3).damping(0.01))
//!     .shear(1e3)
//!     .bend(50.0)
//!     .pin_corners([Corner::TopLeft, Corner::TopRight])
//!     .build()?
//!     .system([0.0, -9.81, 0.0])?;
//! assert_eq!(system.particle_count(), 1600);
//! # Ok::<(), hooke_scenes::SceneError>(())
//! ```
//!
//! # Stiffness: per spring or per material
//!
//! Each spring family takes [`Springs`]: a [`Stiffness`] and a damping.
//! [`Stiffness::PerSpring`]`(k)` gives every spring of the family `k` N/m;
//! [`Stiffness::Modulus`]`(E)` gives each `k = E/L` with `L` its rest length
//! (`E` in N). With `Modulus`, refining keeps the material: `n` springs of
//! length `ℓ/n` in series have stiffness `1/Σ(ℓ/(nE)) = E/ℓ` whatever `n`,
//! whereas `n` springs of `PerSpring(k)` have `k/n`. Damping `c` is per
//! spring (N·s/m) in both.
//!
//! # Mass
//!
//! [`Mass::Total`] in kg or [`Mass::Density`] per unit of the body's measure
//! (kg/m for a rope, kg/m² for cloth and shells, kg/m³ for volumes). The mass
//! is lumped from the elements: each segment, cell, triangle or tet hands
//! its mass in equal parts to its corners, so the particle masses sum to the
//! total.
//!
//! # Bodies
//!
//! | builder | particles | springs ([`Family`]) | volume elements | surface |
//! |---|---|---|---|---|
//! | [`Cloth`] `n × m` (columns × rows) | `nm` | stretch `m(n−1) + n(m−1)`, shear `2(n−1)(m−1)`, bend `m(n−2) + n(m−2)` | none | `2(n−1)(m−1)` triangles |
//! | [`Rope`], `s` segments | `s + 1` | stretch `s`, bend `s − 1` | none | none; `s` segments |
//! | [`Lattice::cubes`] `a × b × c` | `(a+1)(b+1)(c+1)` | edge `a(b+1)(c+1) + …`, face diagonal `2[(a+1)bc + …]`, body diagonal `4abc` | `6abc` (six-tet split) | `4(ab + bc + ca)` triangles |
//! | [`Lattice::tets`] | as above | tet edges: cube edges, one diagonal per face, and for [`TetSplit::Six`] one body diagonal per cube | `5abc` or `6abc`, the springs' tets | as above |
//! | [`Solid`] (tet mesh) | vertices | edge: the unique tet edges | the tets | faces used by one tet |
//! | [`Shell`] (triangle mesh) | vertices | edge: unique edges; bend: across each shared edge, joining the opposite corners | none | the triangles |
//! | [`Layered`] | `2 ×` vertices | edge on both layers, link vertex–copy, cross to the copies of the neighbours | 12 per triangle (its prism's six cuts into 3, averaged) | both layers |
//!
//! - **Cloth** lies in the x–z plane ([`Plane::Horizontal`]) or hangs in the
//!   x–y plane ([`Plane::Vertical`]), may be rotated about an axis and offset;
//!   pins name a [`Corner`], an [`Edge`] or a particle. Stretch springs join
//!   row and column neighbours, shear springs both diagonals of each cell,
//!   bending springs particles two apart in a row or column (the "level-2"
//!   springs that resist folding).
//! - **Rope**: a chain from one point to another with optional skip-one
//!   bending springs and pins at either end.
//! - **Lattice**: a box of cells, either cubes with edge, face-diagonal and
//!   body-diagonal springs (without the diagonals a cube lattice has no
//!   stiffness against shear), or each cube split into 5 or 6 tetrahedra
//!   ([`TetSplit`]) with springs on the tet edges; tet volumes sum to the
//!   box's.
//! - **Solid**: any tetrahedral mesh ([`TetMesh`], from [`tetgen`] files
//!   or built in code). Each tet's mass, density × volume,
//!   goes a quarter to each corner. Tets of zero volume, or oriented
//!   opposite to tet 0 (inverted), are errors naming the tet.
//! - **Shell**: any triangle surface ([`TriangleMesh`], e.g. from [`obj`])
//!   with edge springs and bending springs across shared edges.
//! - **Layered**: the layered model — a closed or open surface copied to an
//!   inner layer at depth `t` along the area-weighted vertex normals,
//!   `x' = x − t n̂`, with springs along both layers, between each vertex and
//!   its copy, and across to the copies of its neighbours. It gives a
//!   surface mesh a volume-like stiffness without a tetrahedral mesh.
//!
//! # Volume
//!
//! Springs know lengths, not volumes: a body of springs and its mirror
//! image have the same spring lengths, so one squashed flat or turned
//! inside out can stay that way. The volumetric bodies — lattices, solids
//! and layered bodies — therefore also carry volume elements: each tet adds
//! the energy `½ κ V₀ (J − 1)²` of its signed volume ratio `J = V/V₀`
//! ([`hooke_core::Tet`]), which pushes a flat or inverted tet back out. By
//! default ([`Volume::Auto`]) `κ` is the bulk modulus of the body's own
//! springs, `κ = Σ k L² / (9 V)`; [`Volume::Modulus`] sets it in Pa, and
//! [`Volume::Off`] keeps the elements with modulus 0, only to measure how
//! many turn inside out ([`hooke_core::System::inversion`]).
//!
//! ```
//! use hooke_scenes::{Lattice, Volume};
//! let jelly = Lattice::cubes(6, 6, 6).size([0.3; 3]).edges(6000.0).build()?;
//! assert_eq!(jelly.tets().len(), 6 * 216);
//! let springs_only = jelly.volume(Volume::Off)?.system([0.0, -9.81, 0.0])?;
//! assert!(springs_only.tets().iter().all(|t| t.modulus == 0.0));
//! # Ok::<(), hooke_scenes::SceneError>(())
//! ```
//!
//! # Collision
//!
//! A body with triangles is a collision surface in the systems it goes into
//! ([`Body::add_to`] calls [`hooke_core::SystemBuilder::surface`]): its
//! points, edges and triangles collide with those of every other surface,
//! and with each other when it self-collides — by default cloth and shells
//! do, the volumetric lattices, solids and layered bodies (whose surface
//! cannot fold onto itself) do not. [`Body::self_collision`],
//! [`Body::thickness`] and [`Body::surface_collision`] change that
//! ([`Collision`]). Only the implicit methods' converged steps keep surfaces
//! apart; the other integrators refuse a system whose surfaces collide.
//!
//! ```
//! use hooke_scenes::Cloth;
//! let cloth = Cloth::grid(10, 10).stretch(1e3).build()?;
//! assert!(cloth.system([0.0, -9.81, 0.0])?.has_surface_contact());
//! // For an explicit integrator: the cloth may then pass through itself.
//! let loose = cloth.self_collision(false).system([0.0, -9.81, 0.0])?;
//! assert!(!loose.has_surface_contact());
//! # Ok::<(), hooke_scenes::SceneError>(())
//! ```
//!
//! # Mesh files
//!
//! - [`obj`]: Wavefront OBJ triangle surfaces, read with `tobj`.
//! - [`tetgen`]: TetGen `.node`/`.ele` tetrahedral meshes; no maintained
//!   crate reads them, so this crate parses them itself, with line-numbered
//!   errors.
//!
//! Gmsh `.msh` files are not read: the one crate that parses them, `mshio`,
//! is unmaintained (it depends on nom 5 and panics on some malformed
//! files). Convert such meshes to TetGen's `.node`/`.ele` format first.
//!
//! # Scene files
//!
//! [`file::load`] and [`file::parse`] read a whole [`Scene`] — timing,
//! integrator, world, bodies, pins and obstacles — from a TOML file
//! (documented in `docs/scene-format.md`); [`builtin`] holds the scenes of
//! the repository's `scenes/` folder, compiled in.
//!
//! # Errors
//!
//! Nothing here panics on user input: bad counts, sizes, masses, stiffnesses,
//! pins, mesh indices, degenerate elements and malformed files all return a
//! [`SceneError`] naming the field, element, vertex, file or line.

mod body;
pub mod builtin;
mod cloth;
mod error;
pub mod file;
mod grid;
mod integrator;
mod lattice;
mod layered;
mod material;
mod mesh;
mod method;
pub mod obj;
mod rope;
mod scene;
mod shell;
mod solid;
mod spring;
mod tet_split;
pub mod tetgen;
mod volume;

pub use body::{Body, Collision, Placement};
pub use cloth::Cloth;
pub use error::{Element, SceneError};
pub use grid::{Corner, Edge, Plane};
pub use hooke_explicit::ExplicitMethod;
pub use integrator::IntegratorSpec;
pub use lattice::Lattice;
pub use layered::Layered;
pub use material::{Mass, Springs, Stiffness};
pub use mesh::{TetMesh, TriangleMesh};
pub use method::{Method, OscillatorStability};
pub use rope::Rope;
pub use scene::{Scene, SceneBody, Timing};
pub use shell::Shell;
pub use solid::Solid;
pub use spring::{BodySpring, Family};
pub use tet_split::TetSplit;
pub use volume::Volume;
