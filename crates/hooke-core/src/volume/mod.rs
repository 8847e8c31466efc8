//! [`Tet`]: a volume element, the energy that keeps a tetrahedron's signed
//! volume near its rest volume and pushes an inverted one back out.

mod svd;

use nalgebra::Matrix3;

use crate::{Mat3, Mat12, Vec3, Vec12};
use svd::signed_svd;

/// A volume element: four particles, their rest volume and the modulus of
/// the energy `½ κ V₀ (J − 1)²`.
///
/// Springs know lengths, not volumes: a tetrahedron and its mirror image
/// have the same edge lengths, so a spring body turned inside out is at
/// rest. A volume element adds the energy
///
/// ```text
/// E = ½ κ V₀ (J − 1)²,   J = V / V₀ = det F,   F = Dₛ Dₘ⁻¹,
/// ```
///
/// with `V` the tetrahedron's signed volume, `V₀ > 0` its rest volume, `κ`
/// the modulus (Pa, a bulk modulus) and `F` the deformation gradient that
/// maps the rest edges `Dₘ = [X₁ − X₀, X₂ − X₀, X₃ − X₀]` to the current
/// ones `Dₛ` (Teschner, Heidelberger, Müller & Gross, *A versatile and
/// robust model for geometrically complex deformable solids*, 2004). It is
/// a polynomial in the positions: finite and smooth for every `J`, a flat
/// (`J = 0`) or inverted (`J < 0`) tetrahedron included, where its force
/// `−κ V₀ (J − 1) ∇J` points toward positive volume (`∇J` is the faces'
/// area-weighted normals divided by `3V₀`), unlike energies with `ln J`,
/// which are infinite there. The springs already carry a body's shape and
/// shear; the element carries the one thing they cannot tell, the sign and
/// size of the volume.
///
/// **Hessian.** `∇²E = κ V₀ (∇J ∇Jᵀ + (J − 1) ∇²J)` is indefinite away
/// from rest. `J` is linear in each vertex, so `∇²J` has zero diagonal
/// blocks and between vertices `a ≠ b` the block `[x_s − x_r]× / 6V₀`
/// (the cross-product matrix, `(a, b, r, s)` an odd permutation of
/// `(0, 1, 2, 3)`): the exact Hessian costs sixteen outer products. In
/// terms of `F = U Σ Vᵀ` (`U`, `V` rotations, `σ₂` negative
/// for an inverted element) it has closed-form eigenpairs (Smith, de Goes
/// & Kim, *Analytic eigensystems for isotropic distortion energies*, 2019):
/// with `E' = κ V₀ (J − 1)`,
///
/// - three twist modes `U (eₐe_bᵀ − e_beₐᵀ) Vᵀ / √2` with eigenvalue
///   `E' σ_c` and three flip modes `U (eₐe_bᵀ + e_beₐᵀ) Vᵀ / √2` with
///   `−E' σ_c` (`{a, b, c} = {0, 1, 2}`);
/// - three scaling modes `U diag(w) Vᵀ`, `w` the eigenvectors of the 3 × 3
///   matrix `κ V₀ g gᵀ + E' A`, `g = (σ₁σ₂, σ₀σ₂, σ₀σ₁)`,
///   `A = [[0, σ₂, σ₁], [σ₂, 0, σ₀], [σ₁, σ₀, 0]]`.
///
/// [`Tet::derivatives`] returns the exact Hessian, the projected one with
/// these negative eigenvalues clamped to zero — positive semidefinite, equal
/// to the exact one where that is, at the cost of one 3 × 3 SVD and one
/// 3 × 3 symmetric eigensolve (nalgebra's `SymmetricEigen`, as for the
/// contact pairs) — or the Gauss–Newton part `κ V₀ ∇J ∇Jᵀ`
/// ([`TetHessian`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tet {
    /// The four particles, ordered so that the rest volume is positive.
    pub vertices: [usize; 4],
    /// The modulus `κ` in Pa (0: the element only measures its volume).
    pub modulus: f64,
    /// The rest volume `V₀ > 0` in m³.
    pub rest_volume: f64,
    /// `Dₘ⁻¹`, the inverse of the rest edge matrix.
    rest_inverse: Mat3,
    /// `1 / 6V₀ = 1 / det Dₘ`.
    ratio_scale: f64,
    /// `V₀^(−1/3)`.
    gradient_scale: f64,
}

/// Which Hessian [`Tet::derivatives`] returns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TetHessian {
    /// `κ V₀ (∇J ∇Jᵀ + (J − 1) ∇²J)`, indefinite away from rest; sixteen
    /// outer products.
    Exact,
    /// The Gauss–Newton part `κ V₀ ∇J ∇Jᵀ` of the energy `½ κ V₀ r²` of the
    /// residual `r = J − 1` (Nocedal & Wright, *Numerical Optimization*,
    /// §10.3): positive semidefinite, exact at rest, off by `κ V₀ |J − 1|
    /// ‖∇²J‖` elsewhere; as cheap as the exact one.
    GaussNewton,
    /// The exact Hessian with its negative eigenvalues (in the basis of the
    /// modes, [`Tet`]'s docs) clamped to zero: positive semidefinite, equal
    /// to the exact one where that is, the closest such matrix; about ten
    /// times the cost (an SVD and a 3 × 3 eigensolve).
    Projected,
}

/// The pairs `(a, b)` of an element's vertices, in the order of
/// [`TetBlocks::pairs`].
pub const TET_PAIRS: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

/// The energy, gradient and Hessian of one element at a configuration, the
/// Hessian in 3 × 3 blocks.
#[derive(Debug, Clone, PartialEq)]
pub struct TetBlocks {
    /// `E`, J.
    pub energy: f64,
    /// `∂E/∂xₐ` for the four vertices, N (minus the forces on them).
    pub gradient: [Vec3; 4],
    /// `∂²E/∂xₐ²` for the four vertices.
    pub diagonal: [Mat3; 4],
    /// `∂²E/∂xₐ∂x_b` for the pairs [`TET_PAIRS`]; the block at `(b, a)` is
    /// its transpose.
    pub pairs: [Mat3; 6],
}

/// The energy, gradient and Hessian of one element at a configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct TetDerivatives {
    /// `E`, J.
    pub energy: f64,
    /// `∂E/∂xₐ` for the four vertices, N (minus the forces on them).
    pub gradient: [Vec3; 4],
    /// `∇²E`, exact or one of its positive-semidefinite stand-ins
    /// ([`TetHessian`]).
    pub hessian: Mat12,
}

impl Tet {
    /// The element on `vertices` at rest at `positions`, reordered (its last
    /// two vertices swapped) if their signed volume is negative; `None` if
    /// the four points are degenerate (a volume below 10⁻¹² of the longest
    /// edge cubed) or not finite.
    #[must_use]
    pub fn at_rest(vertices: [usize; 4], modulus: f64, positions: [Vec3; 4]) -> Option<Self> {
        let mut vertices = vertices;
        let mut p = positions;
        let mut rest = edges(&p);
        let mut volume = rest.determinant() / 6.0;
        let longest = (0..4)
            .flat_map(|a| (a + 1..4).map(move |b| (a, b)))
            .map(|(a, b)| (p[a] - p[b]).norm())
            .fold(0.0, f64::max);
        if !(volume.is_finite() && volume.abs() > 1e-12 * longest.powi(3)) {
            return None;
        }
        if volume < 0.0 {
            vertices.swap(2, 3);
            p.swap(2, 3);
            rest = edges(&p);
            volume = -volume;
        }
        Some(Self {
            vertices,
            modulus,
            rest_volume: volume,
            rest_inverse: rest.try_inverse()?,
            ratio_scale: (6.0 * volume).recip(),
            gradient_scale: volume.cbrt().recip(),
        })
    }

    /// `V₀^(−1/3)`, 1/m: the scale of `|∂J/∂xₐ|` near rest, one over the
    /// element's size.
    #[must_use]
    pub fn gradient_scale(&self) -> f64 {
        self.gradient_scale
    }

    /// The four vertices' positions in `x`.
    fn corners(&self, x: &[Vec3]) -> [Vec3; 4] {
        self.vertices.map(|i| x[i])
    }

    /// The deformation gradient `F = Dₛ Dₘ⁻¹` at positions `x`.
    #[must_use]
    pub fn deformation(&self, x: &[Vec3]) -> Mat3 {
        edges(&self.corners(x)) * self.rest_inverse
    }

    /// The volume ratio `J = V / V₀` at positions `x`: 1 at rest, 0 flat,
    /// negative inverted.
    #[must_use]
    pub fn volume_ratio(&self, x: &[Vec3]) -> f64 {
        let [e1, e2, e3] = edge_vectors(&self.corners(x));
        e1.dot(&e2.cross(&e3)) * self.ratio_scale
    }

    /// `∂J/∂xₐ` for the four vertices at positions `x`, 1/m: the
    /// area-weighted normal of the face opposite vertex `a`, pointing
    /// toward `a`, over `3V₀`.
    #[must_use]
    pub fn volume_gradient(&self, x: &[Vec3]) -> [Vec3; 4] {
        self.ratio_and_gradient(&self.corners(x)).1
    }

    /// `J` and `∇J` at the corners `p`, from the edges `eₐ = pₐ − p₀`:
    /// `6V = e₁ · (e₂ × e₃)`, so `∂J/∂pₐ` is the cross product of the other
    /// two edges (in cyclic order) over `6V₀` for `a = 1, 2, 3`, and minus
    /// their sum for `p₀`, whose move is every edge's. Equal to `det F` and
    /// the cofactor of `F` carried to the vertices, without forming `F`.
    fn ratio_and_gradient(&self, p: &[Vec3; 4]) -> (f64, [Vec3; 4]) {
        let [e1, e2, e3] = edge_vectors(p);
        let s = self.ratio_scale;
        let (g1, g2, g3) = (s * e2.cross(&e3), s * e3.cross(&e1), s * e1.cross(&e2));
        (e1.dot(&g1), [-(g1 + g2 + g3), g1, g2, g3])
    }

    /// The energy `½ κ V₀ (J − 1)²` at positions `x`, J.
    #[must_use]
    pub fn energy(&self, x: &[Vec3]) -> f64 {
        let j = self.volume_ratio(x);
        0.5 * self.modulus * self.rest_volume * (j - 1.0) * (j - 1.0)
    }

    /// The forces `−∂E/∂xₐ` on the four vertices at positions `x`, N.
    #[must_use]
    pub fn forces(&self, x: &[Vec3]) -> [Vec3; 4] {
        self.ratio_and_forces(x).1
    }

    /// The volume ratio `J` and the forces `−∂E/∂xₐ` (as
    /// [`Tet::forces`]) from one deformation gradient: what the energy
    /// `½ κ V₀ (J − 1)²` and the forces need together.
    #[must_use]
    pub fn ratio_and_forces(&self, x: &[Vec3]) -> (f64, [Vec3; 4]) {
        let (j, dj) = self.ratio_and_gradient(&self.corners(x));
        let scale = -self.modulus * self.rest_volume * (j - 1.0);
        (j, dj.map(|g| scale * g))
    }

    /// `[∂⟨P, F⟩/∂xₐ]ₐ`: the gradient in the vertices of a function whose
    /// gradient in `F` is `P` (`F` is linear in the positions).
    fn spread(&self, p: &Mat3) -> [Vec3; 4] {
        let g = p * self.rest_inverse.transpose();
        let (g1, g2, g3): (Vec3, Vec3, Vec3) =
            (g.column(0).into(), g.column(1).into(), g.column(2).into());
        [-(g1 + g2 + g3), g1, g2, g3]
    }

    /// The energy, gradient and Hessian of the kind `hessian` at positions
    /// `x`.
    #[must_use]
    pub fn derivatives(&self, x: &[Vec3], hessian: TetHessian) -> TetDerivatives {
        if hessian == TetHessian::Projected {
            let (j, dj) = self.ratio_and_gradient(&self.corners(x));
            let stiffness = self.modulus * self.rest_volume;
            let slope = stiffness * (j - 1.0);
            return TetDerivatives {
                energy: 0.5 * slope * (j - 1.0),
                gradient: dj.map(|g| slope * g),
                hessian: self.projected_hessian(&self.deformation(x), stiffness, slope),
            };
        }
        let b = self.blocks(x, hessian, 1.0);
        let mut full = Mat12::zeros();
        for (a, block) in b.diagonal.iter().enumerate() {
            full.fixed_view_mut::<3, 3>(3 * a, 3 * a).copy_from(block);
        }
        for (&(a, c), block) in TET_PAIRS.iter().zip(&b.pairs) {
            full.fixed_view_mut::<3, 3>(3 * a, 3 * c).copy_from(block);
            full.fixed_view_mut::<3, 3>(3 * c, 3 * a)
                .copy_from(&block.transpose());
        }
        TetDerivatives {
            energy: b.energy,
            gradient: b.gradient,
            hessian: full,
        }
    }

    /// [`Tet::derivatives`] with the Hessian in blocks, each multiplied by
    /// `scale` (a step's `β²h²`, at no extra cost): for the exact and the
    /// Gauss–Newton Hessian, the blocks `κ V₀ ∇ₐJ ∇_bJᵀ + E' ∂²J/∂xₐ∂x_b`
    /// (`E' = κ V₀ (J − 1)`, or 0 for Gauss–Newton) are formed directly,
    /// without the 12 × 12 matrix.
    #[must_use]
    pub fn blocks(&self, x: &[Vec3], hessian: TetHessian, scale: f64) -> TetBlocks {
        let p = self.corners(x);
        let (j, dj) = self.ratio_and_gradient(&p);
        let stiffness = self.modulus * self.rest_volume;
        let slope = stiffness * (j - 1.0);
        let (energy, gradient) = (0.5 * slope * (j - 1.0), dj.map(|g| slope * g));
        let (stiffness, slope) = (scale * stiffness, scale * slope);
        if hessian == TetHessian::Projected {
            let full = self.projected_hessian(&self.deformation(x), stiffness, slope);
            let block = |a: usize, b: usize| full.fixed_view::<3, 3>(3 * a, 3 * b).into_owned();
            return TetBlocks {
                energy,
                gradient,
                diagonal: std::array::from_fn(|a| block(a, a)),
                pairs: TET_PAIRS.map(|(a, b)| block(a, b)),
            };
        }
        let curvature = if hessian == TetHessian::Exact {
            slope / (6.0 * self.rest_volume)
        } else {
            0.0
        };
        // `k ∇ₐJ ∇_bJᵀ + [d]×` with `d = E'(x_s − x_r)/6V₀`, written out.
        let scaled = dj.map(|g| stiffness * g);
        let mut pairs = [Mat3::zeros(); 6];
        for (pair, &(a, b, r, s)) in pairs.iter_mut().zip(&ODD_PERMUTATION_PAIRS) {
            let (u, w, d) = (scaled[a], dj[b], curvature * (p[s] - p[r]));
            *pair = Mat3::new(
                u.x * w.x,
                u.x * w.y - d.z,
                u.x * w.z + d.y,
                u.y * w.x + d.z,
                u.y * w.y,
                u.y * w.z - d.x,
                u.z * w.x - d.y,
                u.z * w.y + d.x,
                u.z * w.z,
            );
        }
        TetBlocks {
            energy,
            gradient,
            diagonal: std::array::from_fn(|a| scaled[a] * dj[a].transpose()),
            pairs,
        }
    }

    /// The Hessian from the eigenpairs of [`Tet`]'s docs, negative
    /// eigenvalues clamped to zero.
    fn projected_hessian(&self, f: &Mat3, stiffness: f64, slope: f64) -> Mat12 {
        let (u, sigma, v) = signed_svd(f);
        let [s0, s1, s2] = [sigma[0], sigma[1], sigma[2]];
        let mut hessian = Mat12::zeros();
        // Each mode as the matrix `Q = U D Vᵀ`, from the columns of U and V.
        let (uc, vc) = (
            [u.column(0), u.column(1), u.column(2)],
            [v.column(0), v.column(1), v.column(2)],
        );
        let mut add_mode = |lambda: f64, q: Mat3| {
            if lambda <= 0.0 {
                return;
            }
            let w = self.spread(&q);
            let w = Vec12::from_iterator(w.iter().flat_map(|c| c.iter().copied()));
            hessian.ger(lambda, &w, &w, 1.0);
        };
        let r = std::f64::consts::FRAC_1_SQRT_2;
        for (a, b, c) in [(1, 2, 0), (2, 0, 1), (0, 1, 2)] {
            let (ab, ba) = (uc[a] * vc[b].transpose(), uc[b] * vc[a].transpose());
            add_mode(slope * sigma[c], r * (ba - ab));
            add_mode(-slope * sigma[c], r * (ab + ba));
        }
        let g = Vec3::new(s1 * s2, s0 * s2, s0 * s1);
        let a = Matrix3::new(0.0, s2, s1, s2, 0.0, s0, s1, s0, 0.0);
        let scaling = (stiffness * g * g.transpose() + slope * a).symmetric_eigen();
        for k in 0..3 {
            let w = scaling.eigenvectors.column(k);
            let q = (0..3).fold(Mat3::zeros(), |q, i| q + w[i] * uc[i] * vc[i].transpose());
            add_mode(scaling.eigenvalues[k], q);
        }
        hessian
    }
}

/// The vertex pairs `(a, b)` of [`TET_PAIRS`] with the other two vertices
/// `(r, s)` such that `(a, b, r, s)` is an odd permutation of `(0, 1, 2, 3)`:
/// `∂²(6V)/∂xₐ∂x_b = [x_s − x_r]×`, the cross-product matrix (`[w]× y =
/// w × y`), and `∂²(6V)/∂x_b∂xₐ` its transpose `−[x_s − x_r]×`; the
/// diagonal blocks are zero, as `V` is linear in each vertex.
const ODD_PERMUTATION_PAIRS: [(usize, usize, usize, usize); 6] = [
    (0, 1, 3, 2),
    (0, 2, 1, 3),
    (0, 3, 2, 1),
    (1, 2, 3, 0),
    (1, 3, 0, 2),
    (2, 3, 1, 0),
];

/// The edges `[p₁ − p₀, p₂ − p₀, p₃ − p₀]`.
fn edge_vectors(p: &[Vec3; 4]) -> [Vec3; 3] {
    [p[1] - p[0], p[2] - p[0], p[3] - p[0]]
}

/// The edge matrix, [`edge_vectors`] as columns.
fn edges(p: &[Vec3; 4]) -> Mat3 {
    Mat3::from_columns(&edge_vectors(p))
}

#[cfg(test)]
mod tests;
