//! Weak springs carried by their paths: a majorizer of the system matrix
//! with the stiff springs' sparsity, for the factorization.
//!
//! A bending spring joins particles two apart, `i` and `j`, and widens
//! every separator of the factorization's elimination: on a cloth it
//! doubles the factor. Where two springs far stiffer than it join `i` and
//! `j` through a middle particle `m`, its block `K` (positive
//! semidefinite, as the clamp of compressed springs makes it) can move
//! onto theirs. With `a = xᵢ − xₘ`, `b = xₘ − xⱼ` and any `t > 0`,
//!
//! ```text
//! (a + b)ᵀ K (a + b) ≤ (1 + t) aᵀ K a + (1 + 1/t) bᵀ K b,
//! ```
//!
//! as the difference is `(√t a − b/√t)ᵀ K (√t a − b/√t) ≥ 0`. So the matrix
//! with the spring's block replaced by `(1 + t) K` on the leg `(i, m)` and
//! `(1 + 1/t) K` on the leg `(m, j)` is at least the whole one and equals
//! it wherever the path strains uniformly, `b = t a`: `t = L_mj / L_im`,
//! the legs' rest lengths. What it adds elsewhere is at most a fraction
//! [`WEAK`] of each leg's own stiffness (the spring is routed only then),
//! in the directions the legs resist.
//!
//! The springs are considered stiffest first, and a leg is never itself
//! routed, so every route's legs stay in the factor's pattern. Springs
//! whose particles share a volume element keep their own blocks, whose
//! slots carry the element's blocks too.
//!
//! `P` is not `A`: where the path is bent by `θ` at `m`, turning the three
//! particles rigidly about `m` (`a` and `b` turning alike, `a + b` keeping
//! the spring's length) costs `P` an energy `4 L² ω² sin²(θ/2)` times the
//! spring's stiffness, `A` none. On a draped cloth those turns are most of
//! a step's motion, and a Newton step solved with `P` alone is too short
//! along them: on the default scene's cloth 100 times stiffer, at 0.1 s
//! steps, it took 120 iterations a step where `A` takes 40. So the factor
//! of `P` preconditions CG on `A` instead, whose first iterate already
//! scales `P⁻¹r` to `A`'s curvature along it; the same cloth then takes
//! 29 iterations a step.

use hooke_core::{Mat3, System};

use crate::linear::matrix::BlockMatrix;
use crate::linear::neighbours::Neighbours;
use crate::linear::pattern::Pattern;

/// Where weak springs go in the matrix a step factorizes (see the `routes`
/// module of `linear::cholesky`): Newton's sparse Cholesky factor, or the
/// quasi-Newton step's initial Hessian `H₀`.
/// [`Implicit::with_weak_springs`](crate::Implicit::with_weak_springs)
/// chooses; by default Newton's factor keeps them and `H₀` routes them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum WeakSprings {
    /// Every spring's term in its own place: Newton's factor is of the
    /// step's matrix `A` itself and solves it directly; `H₀` is the fast
    /// mass-spring matrix. The default for Newton's factor.
    #[default]
    Kept,
    /// A weak spring joined to its ends' common neighbour by two springs at
    /// least ten times stiffer (a cloth's bending springs, two particles
    /// apart along a row) moves its term onto theirs, scaled so that the
    /// factored matrix `P` is at least the whole one and equals it on
    /// uniform strain: the factor has the stiff springs' sparsity (half
    /// the entries on a cloth).
    ///
    /// In Newton's factor, `P` preconditions CG on `A`, stopped at
    /// Newton's forcing term or `10⁻²`, whichever is tighter: faster where
    /// the factorization dominates and contact couples no particles
    /// outside the pattern (the default scene: 0.82 of the stepping time);
    /// slower where self-contact makes CG run on every solve anyway (the
    /// cloth-pile scene: 1.10 of the wall time, with more Newton
    /// iterations a step). As the quasi-Newton
    /// step's `H₀` where that is factored, the default there, `P` is simply
    /// the initial Hessian: 0.5–0.9 of the time a step at the same
    /// tolerance on the bench cloth. (Applied by multigrid, `H₀` keeps
    /// every spring.)
    /// `benches/README.md` has the measurements; scene files say
    /// `weak_springs = "routed"`.
    Routed,
}

impl hooke_core::Named for WeakSprings {
    /// `"kept"` and `"routed"`, as scene files (`weak_springs`) and reports
    /// spell them.
    const TABLE: &'static [(Self, &'static str)] =
        &[(Self::Kept, "kept"), (Self::Routed, "routed")];
}

/// A spring is routed only if the stiffness it adds to each leg,
/// `(1 + t) k` and `(1 + 1/t) k`, is at most this fraction of the leg's.
const WEAK: f64 = 0.1;

/// A routed spring: its slot, its ends `i < j` (the slot's row and
/// column), the middle particle, the slots of the legs `(i, m)` and
/// `(m, j)`, and their weights `1 + t` and `1 + 1/t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Route {
    pub(crate) slot: u32,
    pub(crate) ends: [u32; 2],
    pub(crate) middle: u32,
    pub(crate) legs: [u32; 2],
    pub(crate) weights: [f64; 2],
}

/// A routed spring by its index (see [`Routes::by_spring`]): the middle
/// particle `m` and the weights of the legs `(s.i, m)` and `(m, s.j)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SpringRoute {
    pub(crate) spring: usize,
    pub(crate) middle: usize,
    pub(crate) weights: [f64; 2],
}

/// The routed springs of a system, by slot (the default: none).
#[derive(Debug, Clone, Default)]
pub(crate) struct Routes {
    routes: Vec<Route>,
    /// Per slot, whether its spring is routed; empty without routes.
    routed: Vec<bool>,
}

impl Routes {
    /// The routes `weak` asks for in `system`'s `pattern` (none, holding
    /// nothing, for [`WeakSprings::Kept`]).
    pub(crate) fn of(system: &System, pattern: &Pattern, weak: WeakSprings) -> Self {
        match weak {
            WeakSprings::Routed => Self::new(system, pattern),
            WeakSprings::Kept => Self::default(),
        }
    }

    /// The routes of `system`'s weak springs in `pattern` (see the module
    /// docs).
    pub(crate) fn new(system: &System, pattern: &Pattern) -> Self {
        let springs = system.springs();
        let mut routed = vec![false; pattern.slots()];
        let mut coupled = vec![false; pattern.slots()];
        for tet in system.tets() {
            let v = tet.vertices;
            for (a, b) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
                if let Some(t) = pattern.slot_between(v[a], v[b]) {
                    coupled[t] = true;
                }
            }
        }
        let neighbours = Neighbours::new(pattern);
        let mut order: Vec<u32> = (0..pattern.slots() as u32).collect();
        order.sort_by(|&s, &t| {
            let k = |t: u32| springs[pattern.spring(t as usize)].stiffness;
            k(t).total_cmp(&k(s))
        });
        let mut routes = Vec::new();
        for t in order {
            let t = t as usize;
            let spring = &springs[pattern.spring(t)];
            if coupled[t] || spring.stiffness <= 0.0 || spring.rest_length <= 0.0 {
                continue;
            }
            let (i, j) = (pattern.row_of(t), pattern.column(t));
            let mut best: Option<(f64, Route)> = None;
            for &(m, first) in neighbours.of(i) {
                let (m, first) = (m as usize, first as usize);
                if m == j || routed[first] {
                    continue;
                }
                let Some(second) = pattern.slot_between(m, j) else {
                    continue;
                };
                if routed[second] {
                    continue;
                }
                let (a, b) = (
                    &springs[pattern.spring(first)],
                    &springs[pattern.spring(second)],
                );
                if a.rest_length <= 0.0 || b.rest_length <= 0.0 {
                    continue;
                }
                let path = a.rest_length + b.rest_length;
                let weights = [path / a.rest_length, path / b.rest_length];
                let weak = spring.stiffness * weights[0] <= WEAK * a.stiffness
                    && spring.stiffness * weights[1] <= WEAK * b.stiffness;
                if weak && best.as_ref().is_none_or(|(shortest, _)| path < *shortest) {
                    let route = Route {
                        slot: t as u32,
                        ends: [i as u32, j as u32],
                        middle: m as u32,
                        legs: [first as u32, second as u32],
                        weights,
                    };
                    best = Some((path, route));
                }
            }
            if let Some((_, route)) = best {
                routed[t] = true;
                routes.push(route);
            }
        }
        routes.sort_unstable_by_key(|r| r.slot);
        Self { routes, routed }
    }

    /// Whether the spring in `slot` is routed.
    #[inline]
    pub(crate) fn is_routed(&self, slot: usize) -> bool {
        self.routed.get(slot).copied().unwrap_or(false)
    }

    /// The `(neighbour, slot)` pairs of `neighbours` whose spring keeps its
    /// place: the edges of the factor's graph.
    pub(crate) fn kept<'a>(
        &'a self,
        neighbours: &'a [(u32, u32)],
    ) -> impl Iterator<Item = &'a (u32, u32)> + 'a {
        neighbours
            .iter()
            .filter(|&&(_, t)| !self.is_routed(t as usize))
    }

    /// The routes, by slot.
    pub(crate) fn iter(&self) -> impl Iterator<Item = &Route> {
        self.routes.iter()
    }

    /// The routes by spring, `pattern` the one they were found in: for each
    /// routed spring `s`, in the order of the springs, its index, its
    /// middle particle and the weights of its legs from `s.i` and from
    /// `s.j`.
    pub(crate) fn by_spring(&self, system: &System, pattern: &Pattern) -> Vec<SpringRoute> {
        let mut routes: Vec<SpringRoute> = self
            .routes
            .iter()
            .map(|route| {
                let spring = pattern.spring(route.slot as usize);
                let [wi, wj] = route.weights;
                let forward = system.springs()[spring].i == route.ends[0] as usize;
                SpringRoute {
                    spring,
                    middle: route.middle as usize,
                    weights: if forward { [wi, wj] } else { [wj, wi] },
                }
            })
            .collect();
        routes.sort_unstable_by_key(|r| r.spring);
        routes
    }

    /// Whether no spring is routed.
    pub(crate) fn is_empty(&self) -> bool {
        self.routes.is_empty()
    }

    /// Fills `carried` with what moving the routed springs' blocks of `a`
    /// onto their paths adds: each block `K` leaves its ends' diagonals
    /// and its slot, and `K⁺ ⪰ K`, `K` raised to positive semidefinite
    /// ([`raised_semidefinite`]: the exact blocks of compressed springs
    /// are indefinite, and a path bounds only a positive semidefinite
    /// block), joins the legs' — `(1 + t) K⁺` on `(i, m)`, `(1 + 1/t) K⁺`
    /// on `(m, j)`, their diagonals included.
    pub(crate) fn carry(&self, a: &BlockMatrix, carried: &mut Carried) {
        if self.is_empty() {
            return;
        }
        carried.diagonal.fill(Mat3::zeros());
        carried.slots.fill(Mat3::zeros());
        for route in &self.routes {
            let own = a.springs[route.slot as usize].to_mat3();
            let block = raised_semidefinite(own);
            let [i, j] = route.ends.map(|e| e as usize);
            let [wi, wj] = route.weights;
            carried.diagonal[i] += wi * block - own;
            carried.diagonal[j] += wj * block - own;
            carried.diagonal[route.middle as usize] += (wi + wj) * block;
            // A slot holds `−K` of its spring.
            carried.slots[route.legs[0] as usize] -= wi * block;
            carried.slots[route.legs[1] as usize] -= wj * block;
        }
    }
}

/// What [`Routes::carry`] adds to each particle's diagonal block and each
/// slot's block (empty without routes).
#[derive(Debug, Clone, Default)]
pub(crate) struct Carried {
    diagonal: Vec<Mat3>,
    slots: Vec<Mat3>,
}

impl Carried {
    /// Room for `routes` over `particles` and `slots`.
    pub(crate) fn new(routes: &Routes, particles: usize, slots: usize) -> Self {
        if routes.is_empty() {
            return Self::default();
        }
        Self {
            diagonal: vec![Mat3::zeros(); particles],
            slots: vec![Mat3::zeros(); slots],
        }
    }

    /// What the routes add to particle `i`'s diagonal block (`None`
    /// without routes).
    #[inline]
    pub(crate) fn diagonal(&self, i: usize) -> Option<&Mat3> {
        self.diagonal.get(i)
    }

    /// What the routes add to the block of `slot` (`None` without routes).
    #[inline]
    pub(crate) fn slot(&self, slot: usize) -> Option<&Mat3> {
        self.slots.get(slot)
    }
}

/// `K + max(0, −λ_min(K)) I`: the symmetric block `K` itself where it is
/// positive semidefinite (every principal minor non-negative), otherwise
/// raised by its most negative eigenvalue (in closed form, Smith 1961).
/// For a spring's block `k∥ d dᵀ + k⊥ (I − d dᵀ)` with `k⊥ < 0` that is
/// `(k∥ − k⊥) d dᵀ`, at least the clamped block `k∥ d dᵀ`.
fn raised_semidefinite(k: Mat3) -> Mat3 {
    let minors = [
        k[(0, 0)],
        k[(1, 1)],
        k[(2, 2)],
        k[(0, 0)] * k[(1, 1)] - k[(0, 1)] * k[(0, 1)],
        k[(0, 0)] * k[(2, 2)] - k[(0, 2)] * k[(0, 2)],
        k[(1, 1)] * k[(2, 2)] - k[(1, 2)] * k[(1, 2)],
        k.determinant(),
    ];
    if minors.iter().all(|&m| m >= 0.0) {
        return k;
    }
    let off = k[(0, 1)].powi(2) + k[(0, 2)].powi(2) + k[(1, 2)].powi(2);
    let q = k.trace() / 3.0;
    let p =
        (((k[(0, 0)] - q).powi(2) + (k[(1, 1)] - q).powi(2) + (k[(2, 2)] - q).powi(2) + 2.0 * off)
            / 6.0)
            .sqrt();
    let smallest = if p == 0.0 {
        q
    } else {
        let b = (k - q * Mat3::identity()) / p;
        let phi = (0.5 * b.determinant()).clamp(-1.0, 1.0).acos() / 3.0;
        q + 2.0 * p * (phi + 2.0 * std::f64::consts::FRAC_PI_3).cos()
    };
    k + (-smallest).max(0.0) * Mat3::identity()
}
