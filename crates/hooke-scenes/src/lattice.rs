//! [`Lattice`]: a box of `nx × ny × nz` cells, springs on the cubes or on a
//! split of each cube into tetrahedra.

use hooke_core::Vec3;

use crate::body::Body;
use crate::error::{SceneError, count, finite_vector, grid_points, positive};
use crate::material::{Mass, Springs};
use crate::mesh::{TET_EDGES, TetMesh, lump};
use crate::spring::{Family, SpringSet, validate_families};
use crate::tet_split::{TetSplit, cell_tets};
use crate::volume::{Volume, positively_oriented};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Connectivity {
    Cubes,
    Tets(TetSplit),
}

/// A box lattice of `(nx + 1)(ny + 1)(nz + 1)` particles, particle
/// `(k (ny + 1) + j)(nx + 1) + i` at grid point `(i, j, k)`.
///
/// Springs are grouped by their span within a cell: [`Family::Edge`] along
/// a cube edge, [`Family::FaceDiagonal`] across a face, and
/// [`Family::BodyDiagonal`] through the cube; a family not set is absent.
///
/// Volume elements ([`Body::tets`], see [`Volume`]): every cube split into
/// tetrahedra — the connectivity's own split for [`Lattice::tets`], and for
/// [`Lattice::cubes`], whose springs are not on tets, the six-tet Kuhn
/// split ([`TetSplit::Six`]) around each cube's diagonal from `(i, j, k)`
/// to `(i + 1, j + 1, k + 1)`, which needs no alternation between
/// neighbours: `6 nx ny nz` elements (`5 nx ny nz` for [`TetSplit::Five`])
/// whose volumes sum to the box's.
///
/// ```
/// use hooke_scenes::{Family, Lattice, Springs, TetSplit};
/// let cubes = Lattice::cubes(2, 2, 2).edges(1e3).face_diagonals(5e2).body_diagonals(5e2).build()?;
/// assert_eq!(cubes.springs_of(Family::BodyDiagonal).count(), 4 * 8);
/// let tets = Lattice::tets(2, 2, 2, TetSplit::Six).edges(Springs::modulus(1e3)).build()?;
/// assert_eq!(tets.springs().len(), 3 * 2 * 3 * 3);
/// # Ok::<(), hooke_scenes::SceneError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct Lattice {
    cells: [usize; 3],
    connectivity: Connectivity,
    size: [f64; 3],
    origin: [f64; 3],
    mass: Mass,
    edges: Option<Springs>,
    face_diagonals: Option<Springs>,
    body_diagonals: Option<Springs>,
    volume: Volume,
    pins: Vec<usize>,
}

impl Lattice {
    /// Cubes with springs on their edges, both diagonals of every face and
    /// all four body diagonals (each shared spring once).
    pub fn cubes(nx: usize, ny: usize, nz: usize) -> Self {
        Self::new([nx, ny, nz], Connectivity::Cubes)
    }

    /// Cubes split into tetrahedra, springs on the tets' edges (each shared
    /// edge once).
    pub fn tets(nx: usize, ny: usize, nz: usize, split: TetSplit) -> Self {
        Self::new([nx, ny, nz], Connectivity::Tets(split))
    }

    fn new(cells: [usize; 3], connectivity: Connectivity) -> Self {
        Self {
            cells,
            connectivity,
            size: [1.0; 3],
            origin: [0.0; 3],
            mass: Mass::Density(1000.0),
            edges: None,
            face_diagonals: None,
            body_diagonals: None,
            volume: Volume::Auto,
            pins: Vec::new(),
        }
    }

    /// The box's extent along x, y and z in m (default 1 m each).
    ///
    /// ```
    /// let box_ = hooke_scenes::Lattice::cubes(1, 1, 1).size([2.0, 1.0, 0.5]).build()?;
    /// assert_eq!(box_.positions()[7], hooke_core::Vec3::new(2.0, 1.0, 0.5));
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn size(mut self, size: [f64; 3]) -> Self {
        self.size = size;
        self
    }

    /// The box's minimum corner in m (default the origin).
    ///
    /// ```
    /// let box_ = hooke_scenes::Lattice::cubes(1, 1, 1).origin([0.0, 3.0, 0.0]).build()?;
    /// assert_eq!(box_.positions()[0], hooke_core::Vec3::new(0.0, 3.0, 0.0));
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn origin(mut self, origin: [f64; 3]) -> Self {
        self.origin = origin;
        self
    }

    /// Total mass, or density in kg/m³ (default 1000 kg/m³); lumped an
    /// eighth of each cube's mass to each corner, or a quarter of each
    /// tet's.
    ///
    /// ```
    /// use hooke_scenes::{Lattice, Mass};
    /// let box_ = Lattice::cubes(1, 1, 1).mass(Mass::Total(8.0)).build()?;
    /// assert_eq!(box_.masses(), [1.0; 8]);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn mass(mut self, mass: Mass) -> Self {
        self.mass = mass;
        self
    }

    /// Springs along cube edges.
    ///
    /// ```
    /// let box_ = hooke_scenes::Lattice::cubes(1, 1, 1).edges(1e3).build()?;
    /// assert_eq!(box_.springs().len(), 12);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn edges(mut self, springs: impl Into<Springs>) -> Self {
        self.edges = Some(springs.into());
        self
    }

    /// Springs across cube faces (both diagonals for cubes, the split's one
    /// for tets).
    ///
    /// ```
    /// let box_ = hooke_scenes::Lattice::cubes(1, 1, 1).face_diagonals(1e3).build()?;
    /// assert_eq!(box_.springs().len(), 12);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn face_diagonals(mut self, springs: impl Into<Springs>) -> Self {
        self.face_diagonals = Some(springs.into());
        self
    }

    /// Springs through cubes (all four for cubes, the split's one for
    /// [`TetSplit::Six`], none for [`TetSplit::Five`]).
    ///
    /// ```
    /// let box_ = hooke_scenes::Lattice::cubes(1, 1, 1).body_diagonals(1e3).build()?;
    /// assert_eq!(box_.springs().len(), 4);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn body_diagonals(mut self, springs: impl Into<Springs>) -> Self {
        self.body_diagonals = Some(springs.into());
        self
    }

    /// The modulus of the volume elements (default [`Volume::Auto`]: the
    /// bulk modulus `κ = Σ k L² / (9 V)` of the lattice's springs, see
    /// [`Volume`] for why).
    ///
    /// ```
    /// use hooke_scenes::{Lattice, Volume};
    /// let cube = Lattice::cubes(2, 2, 2).edges(1e3).volume(Volume::Modulus(2e4)).build()?;
    /// assert_eq!((cube.tets().len(), cube.volume_modulus()), (48, 2e4));
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn volume(mut self, volume: Volume) -> Self {
        self.volume = volume;
        self
    }

    /// Pins particle `(k (ny + 1) + j)(nx + 1) + i`.
    ///
    /// ```
    /// let box_ = hooke_scenes::Lattice::cubes(1, 1, 1).pin(0).pin(1).build()?;
    /// assert_eq!(box_.pins(), [0, 1]);
    /// # Ok::<(), hooke_scenes::SceneError>(())
    /// ```
    pub fn pin(mut self, particle: usize) -> Self {
        self.pins.push(particle);
        self
    }

    /// Validates the description and builds the body. Its surface is the
    /// box's outside, two triangles per boundary cell face.
    ///
    /// # Errors
    /// [`SceneError`] naming the first bad field: a zero cell count, a size
    /// that is not finite and positive, an origin that is not finite, a
    /// mass, spring parameter or volume modulus out of range, or a pin out
    /// of range.
    pub fn build(self) -> Result<Body, SceneError> {
        let [nx, ny, nz] = [
            count("lattice cells along x", self.cells[0], 1)?,
            count("lattice cells along y", self.cells[1], 1)?,
            count("lattice cells along z", self.cells[2], 1)?,
        ];
        grid_points("lattice cells", &[nx, ny, nz], 1)?;
        let size = [
            positive("lattice size along x", self.size[0])?,
            positive("lattice size along y", self.size[1])?,
            positive("lattice size along z", self.size[2])?,
        ];
        let origin = finite_vector("lattice origin", self.origin)?;
        let total = self.mass.total(size.iter().product())?;
        let families = [
            (Family::Edge, self.edges),
            (Family::FaceDiagonal, self.face_diagonals),
            (Family::BodyDiagonal, self.body_diagonals),
        ];
        validate_families(&families)?;
        let index = |[i, j, k]: [usize; 3]| (k * (ny + 1) + j) * (nx + 1) + i;
        let mut grid = Vec::new();
        for k in 0..=nz {
            for j in 0..=ny {
                for i in 0..=nx {
                    grid.push([i, j, k]);
                }
            }
        }
        let spacing = Vec3::new(
            size[0] / nx as f64,
            size[1] / ny as f64,
            size[2] / nz as f64,
        );
        let positions: Vec<Vec3> = grid
            .iter()
            .map(|p| origin + Vec3::from(p.map(|c| c as f64)).component_mul(&spacing))
            .collect();
        let mut cubes = Vec::with_capacity(nx * ny * nz);
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    cubes.push([i, j, k]);
                }
            }
        }
        let corner =
            |[i, j, k]: [usize; 3], c: usize| index([i + (c & 1), j + (c >> 1 & 1), k + (c >> 2)]);
        let split = match self.connectivity {
            Connectivity::Tets(split) => split,
            Connectivity::Cubes => TetSplit::Six,
        };
        let mut mesh = TetMesh {
            vertices: positions.clone(),
            tets: Vec::new(),
        };
        for &cube in &cubes {
            let odd = cube.iter().sum::<usize>() % 2 == 1;
            for tet in cell_tets(split, odd) {
                mesh.tets.push(positively_oriented(
                    tet.map(|c| corner(cube, c)),
                    &positions,
                ));
            }
        }
        let (volumes, _) = mesh.checked_volumes()?;
        let pairs: Vec<(usize, usize)> = match self.connectivity {
            Connectivity::Cubes => cubes
                .iter()
                .flat_map(|&cube| {
                    (0..8)
                        .flat_map(move |c| (c + 1..8).map(move |d| (c, d)))
                        .map(move |(c, d)| (corner(cube, c), corner(cube, d)))
                })
                .collect(),
            Connectivity::Tets(_) => mesh
                .tets
                .iter()
                .flat_map(|t| TET_EDGES.map(|(c, d)| (t[c], t[d])))
                .collect(),
        };
        let mut springs = SpringSet::new(&positions);
        for (a, b) in pairs {
            // A pair within one cell spans 1, 2 or 3 axes: edge, face or body diagonal.
            let span = (0..3).filter(|&d| grid[a][d] != grid[b][d]).count();
            let (family, params) = families[span - 1];
            springs.add(a, b, family, params)?;
        }
        let masses = match self.connectivity {
            Connectivity::Tets(_) => lump(positions.len(), &mesh.tets, &volumes, total),
            Connectivity::Cubes => {
                let cube_corners: Vec<[usize; 8]> = cubes
                    .iter()
                    .map(|&cube| std::array::from_fn(|c| corner(cube, c)))
                    .collect();
                lump(
                    positions.len(),
                    &cube_corners,
                    &vec![1.0; cubes.len()],
                    total,
                )
            }
        };
        let triangles = mesh.boundary_faces(1.0);
        let springs = springs.into_springs();
        Body::from_parts(
            masses,
            positions,
            springs,
            self.pins,
            (triangles, false),
            Vec::new(),
        )?
        .with_tets(mesh.tets, self.volume)
    }
}
