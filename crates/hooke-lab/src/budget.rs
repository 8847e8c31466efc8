//! [`EnergyBudget`]: the observer that decides whether a run stayed
//! stable.

use std::ops::ControlFlow;

use hooke_core::{Observer, Path, State, StepInfo, StepStart, System, Term, Vec3, When};

/// The energy test of a stability run.
///
/// The energy is that of the moving parts,
/// `E = Σ_free ½ mᵢ|vᵢ|² + Σ ½ k (l − L)² + Σ_terms E_term` (kinetic
/// energy of the free particles, the springs' elastic energy and the
/// energy of the system's own terms, [`System::terms`], [`Term::energy`]),
/// and gravity, scripted pins and the terms' external agents (a wind)
/// count as external forces doing work on it:
///
/// ```text
/// W(t) = Σ_free mᵢ g·(xᵢ(t) − xᵢ(0))  +  ∫₀ᵗ −Σ_scripted vₚ·fₚ dt  +  Σ_steps Σ_terms W_term
/// ```
///
/// where `fₚ` is the total spring force on scripted pin `p` (the integral
/// by the trapezoidal rule over the steps), and `W_term` is each term's
/// work over each recorded step from `(xₙ, vₙ)` to `(xₙ₊₁, vₙ₊₁)`
/// ([`Term::work`], after [`Term::begin`] at the step's start, with
/// `βh = h` as the budget does not know the integrator): the quantity an
/// implicit step's energy test allows for, by the term's own rule (a
/// wind's, `h Σ_T F_T(vₙ₊₁)·w` with the triangles at the step's start,
/// first order in `h`). For the exact motion
/// `E(t) = E(0) + W(t) − D(t)` with the dissipated energy `D ≥ 0` (spring
/// and air damping, inelastic contacts with fixed obstacles), so the
/// *energy gain*
///
/// ```text
/// G(t) = E(t) − E(0) − W(t)
/// ```
///
/// is at most zero for the exact motion, and positive where an integrator
/// created energy. The *energy ratio* at time `t` measures the gain
/// against the largest energy the exact motion could have reached by then,
/// the allowance `A(t) = E(0) + max_{s≤t} W(s)`:
///
/// ```text
/// ratio(t) = 1 + G(t) / A(t),      A(t) = E(0) + max_{s≤t} W(s).
/// ```
///
/// It is one for the exact, undamped motion (below one with dissipation),
/// whatever the origin of the coordinates, and exceeds one by the gain's
/// fraction of the allowance at every instant the energy is above
/// `E(0) + W(t)` — also while gravity's work is below its largest so far,
/// where `E(t) / A(t)` would hide a gain up to `max W − W(t)`. A ratio
/// below a bound `b` means `E(t) ≤ E(0) + W(t) + (b − 1) A(t) ≤ b A(t)`.
/// The ratio is not defined while `A` is zero (a system at rest before
/// gravity has done any work), and those instants are skipped; the gain
/// is recorded at every instant. Work done by moving obstacles is not
/// counted, so on scenes with moving obstacles the gain can be positive
/// physically.
///
/// Gravity's work is path-independent, `mᵢ g·Δxᵢ`, and is computed exactly
/// from the positions: the budget adds no error of its own to what it
/// measures, so on the oscillator the gain it reports is the one the
/// integrator's amplification factor gives, to rounding (the tests
/// `the_reported_ratio_is_the_amplification_factors_at_small_steps` and
/// `the_reported_gain_is_the_theorys_at_every_stiffness`).
/// Only the pins' and the terms' work, which depend on the path, are
/// summed over the steps.
///
/// As an [`Observer`] (called after every step) it records each state and
/// stops the run at the first ratio above its [bound](Self::with_bound) or
/// not a number.
#[derive(Debug, Clone)]
pub struct EnergyBudget {
    free: Vec<usize>,
    masses: Vec<f64>,
    start: Vec<Vec3>,
    gravity: Option<Vec3>,
    scripted: Vec<usize>,
    initial: f64,
    pin_work: f64,
    pin_power: f64,
    max_work: f64,
    max_ratio: f64,
    max_gain: f64,
    max_gain_time: f64,
    time: f64,
    bound: f64,
    exceeded: bool,
    /// Copies of the system's own terms, which lag state over a step.
    terms: Vec<Box<dyn Term>>,
    /// `Σ_steps Σ_terms W_term` so far, J.
    term_work: f64,
    /// Positions and velocities of the last recorded state, the start of
    /// the next step's term work (empty without terms).
    last: (Vec<Vec3>, Vec<Vec3>),
}

impl EnergyBudget {
    /// The budget of `system` starting from its initial state.
    #[must_use]
    pub fn new(system: &System) -> Self {
        let state = system.initial_state();
        let free: Vec<usize> = (0..system.particle_count())
            .filter(|&i| !system.is_pinned(i))
            .collect();
        let scripted = system
            .pin_paths()
            .iter()
            .filter(|(_, path)| !matches!(path, Path::Fixed))
            .map(|&(p, _)| p)
            .collect();
        let terms = system.terms().to_vec();
        let last = if terms.is_empty() {
            (Vec::new(), Vec::new())
        } else {
            (state.positions().to_vec(), state.velocities().to_vec())
        };
        let mut budget = Self {
            masses: system.masses().to_vec(),
            start: state.positions().to_vec(),
            gravity: system.gravity(),
            free,
            scripted,
            initial: 0.0,
            pin_work: 0.0,
            pin_power: 0.0,
            max_work: 0.0,
            max_ratio: 0.0,
            max_gain: f64::NEG_INFINITY,
            max_gain_time: state.time(),
            time: state.time(),
            bound: f64::INFINITY,
            exceeded: false,
            terms,
            term_work: 0.0,
            last,
        };
        budget.initial = budget.energy(system, &state);
        budget.pin_power = budget.pin_power(system, &state);
        budget
    }

    /// The same budget stopping a run, as an [`Observer`], once the ratio
    /// exceeds `bound`.
    #[must_use]
    pub fn with_bound(self, bound: f64) -> Self {
        Self { bound, ..self }
    }

    /// Whether a ratio above the bound (or not a number) was seen.
    #[must_use]
    pub fn exceeded(&self) -> bool {
        self.exceeded
    }

    /// `E` of `state`, J.
    #[must_use]
    pub fn energy(&self, system: &System, state: &State) -> f64 {
        let (x, v) = (state.positions(), state.velocities());
        let kinetic: f64 = self
            .free
            .iter()
            .map(|&i| 0.5 * self.masses[i] * v[i].norm_squared())
            .sum();
        let elastic: f64 = system
            .springs()
            .iter()
            .map(|s| s.energy(x[s.i], x[s.j]))
            .sum();
        // A term evaluates with scratch of its own, so it is asked on a
        // copy, as `System::energy` does: nothing for a system without.
        let terms: f64 = system
            .terms()
            .iter()
            .map(|t| t.clone_box().energy(system, x, v, When::End).value)
            .sum();
        kinetic + elastic + terms
    }

    /// `E(0)`, J.
    #[must_use]
    pub fn initial(&self) -> f64 {
        self.initial
    }

    fn gravity_work(&self, state: &State) -> f64 {
        self.gravity.map_or(0.0, |g| {
            let x = state.positions();
            self.free
                .iter()
                .map(|&i| self.masses[i] * g.dot(&(x[i] - self.start[i])))
                .sum()
        })
    }

    /// `−Σ_scripted vₚ·fₚ`: the power the scripted pins put into the
    /// springs.
    fn pin_power(&self, system: &System, state: &State) -> f64 {
        if self.scripted.is_empty() {
            return 0.0;
        }
        let (x, v) = (state.positions(), state.velocities());
        system
            .springs()
            .iter()
            .map(|s| {
                let fi = s.force(x[s.i], x[s.j], v[s.i], v[s.j]);
                let on_i = if self.scripted.contains(&s.i) {
                    -v[s.i].dot(&fi)
                } else {
                    0.0
                };
                let on_j = if self.scripted.contains(&s.j) {
                    v[s.j].dot(&fi)
                } else {
                    0.0
                };
                on_i + on_j
            })
            .sum()
    }

    /// Adds the terms' work over the step from the last recorded state to
    /// `state` to `Σ_steps Σ_terms W_term`, and keeps `state` as the next
    /// step's start.
    fn add_term_work(&mut self, system: &System, state: &State) {
        if self.terms.is_empty() {
            return;
        }
        let (x, v) = (state.positions(), state.velocities());
        let (x0, v0) = &mut self.last;
        let h = state.time() - self.time;
        let step = StepStart {
            x: x0,
            v: v0,
            time: self.time,
            h,
            beta_h: h,
        };
        for term in &mut self.terms {
            term.begin(system, &step);
            self.term_work += term.work(system, &step, x, v);
        }
        x0.copy_from_slice(x);
        v0.copy_from_slice(v);
    }

    /// Records `state` (the state after the next step) and returns its
    /// energy ratio, or `None` while the ratio is not defined.
    pub fn record(&mut self, system: &System, state: &State) -> Option<f64> {
        self.add_term_work(system, state);
        if !self.scripted.is_empty() {
            let power = self.pin_power(system, state);
            self.pin_work += 0.5 * (self.pin_power + power) * (state.time() - self.time);
            self.pin_power = power;
        }
        self.time = state.time();
        let work = self.gravity_work(state) + self.pin_work + self.term_work;
        self.max_work = self.max_work.max(work);
        let allowance = self.initial + self.max_work;
        let gain = self.energy(system, state) - (self.initial + work);
        if gain > self.max_gain || gain.is_nan() {
            self.max_gain = if gain.is_nan() { f64::INFINITY } else { gain };
            self.max_gain_time = self.time;
        }
        let ratio = if allowance > 0.0 {
            1.0 + gain / allowance
        } else if gain.is_nan() {
            f64::NAN
        } else {
            return None;
        };
        // NaN never compares greater, so record it explicitly.
        if ratio.is_nan() {
            self.max_ratio = f64::INFINITY;
        } else if ratio > self.max_ratio {
            self.max_ratio = ratio;
        }
        self.exceeded |= ratio.is_nan() || ratio > self.bound;
        Some(ratio)
    }

    /// The largest energy ratio `1 + G(t) / A(t)` seen so far (infinite
    /// once the energy was not finite; zero if the ratio was never
    /// defined).
    #[must_use]
    pub fn max_ratio(&self) -> f64 {
        self.max_ratio
    }

    /// `E(0) + max W` so far, J: the largest energy the exact motion could
    /// have reached, the scale the ratio and the gain are measured against.
    #[must_use]
    pub fn allowance(&self) -> f64 {
        self.initial + self.max_work
    }

    /// The largest energy gain `E(t) − E(0) − W(t)` over the recorded
    /// states, J, and the time it was reached: at most zero for the exact
    /// motion (dissipation only lowers it), positive where the integrator
    /// created energy; infinite once the energy was not finite, and
    /// `(−∞, 0)` before any state was recorded.
    #[must_use]
    pub fn max_gain(&self) -> (f64, f64) {
        (self.max_gain, self.max_gain_time)
    }
}

impl Observer for EnergyBudget {
    fn observe(&mut self, system: &System, state: &State, _step: &StepInfo) -> ControlFlow<()> {
        self.record(system, state);
        if self.exceeded {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}

#[cfg(test)]
mod tests;
