//! Stability maps of the `oscillator` scene against theory.
//!
//! The scene is one bob (m = 1 kg) on a zero-length spring (k = 1 N/m,
//! ω = 1 rad/s at stiffness scale 1), released at rest 1 m above its
//! equilibrium under gravity g = 2 m/s². Every method here is linear on
//! this problem, so each step multiplies the deviation from equilibrium,
//! written `w = (u − u_eq) + i v/ω`, by a complex amplification factor
//! `R(iθ)` with `θ = hω` (for the Runge–Kutta methods `R` is the Taylor
//! polynomial of `e^(iθ)` of their order). That gives an independent
//! computation of every energy gain and ratio the sweep measures.

use std::sync::OnceLock;

use hooke_core::{System, Vec3};
use hooke_lab::{Method, OscillatorStability, StabilityOptions, StabilityReport, stability};
use hooke_scenes::{ExplicitMethod, builtin};

/// The default sweep, with 0.1 s of simulated time per cell (and the
/// default 1000 steps at least), without Dormand–Prince: at stiffness
/// scale 10⁹ its error control takes thousands of substeps per step, which
/// makes it by far the slowest method of the sweep, and it has no step
/// limit to check.
fn sweep() -> &'static StabilityReport {
    static REPORT: OnceLock<StabilityReport> = OnceLock::new();
    REPORT.get_or_init(|| {
        let scene = builtin::load("oscillator").unwrap();
        let mut options = StabilityOptions::for_scene(&scene);
        options.duration = 0.1;
        options.methods.retain(|&m| m != Method::DormandPrince);
        stability(&scene, &options, &|_, _| {}).unwrap()
    })
}

/// The largest energy ratio `1 + G/(E(0) + max W)`, `G = E − E(0) − W`,
/// of the exact discrete motion of a one-step method with amplification
/// `r = R(−iθ)` over `steps` steps, stopping at the first ratio above
/// `bound` as the sweep does.
///
/// At stiffness scale `s` the spring has k = s (m = 1, g = 2); the bob
/// starts at rest with the spring stretched by 1 m, and its equilibrium is
/// at a drop `d* = 2/s − 1` below the start. For a drop `d`,
/// `E = ½v² + ½k(1 + d)²`, `E(0) = ½k` and `W = 2d`.
fn expected_ratio(r: (f64, f64), scale: f64, steps: usize, bound: f64) -> f64 {
    let (k, omega) = (scale, scale.sqrt());
    let equilibrium = 2.0 / k - 1.0;
    // w = (d − d*) + i v/ω.
    let (mut re, mut im) = (-equilibrium, 0.0_f64);
    let (mut max_work, mut max_ratio) = (0.0_f64, 0.0_f64);
    for _ in 0..steps {
        (re, im) = (re * r.0 - im * r.1, re * r.1 + im * r.0);
        let (drop, v) = (equilibrium + re, omega * im);
        let energy = 0.5 * v * v + 0.5 * k * (1.0 + drop) * (1.0 + drop);
        let work = 2.0 * drop;
        max_work = max_work.max(work);
        let ratio = 1.0 + (energy - 0.5 * k - work) / (0.5 * k + max_work);
        max_ratio = max_ratio.max(ratio);
        if ratio > bound {
            break;
        }
    }
    max_ratio
}

/// `R(−iθ)` of the Runge–Kutta methods of order `p`: `Σ_{k≤p} (−iθ)^k/k!`
/// (the deviation obeys `w' = −iω w`).
fn taylor(theta: f64, order: u32) -> (f64, f64) {
    let (mut re, mut im) = (0.0, 0.0);
    let (mut term_re, mut term_im) = (1.0_f64, 0.0_f64);
    for k in 0..=order {
        re += term_re;
        im += term_im;
        // term *= −iθ/(k+1)
        let scale = theta / f64::from(k + 1);
        (term_re, term_im) = (term_im * scale, -term_re * scale);
    }
    (re, im)
}

/// The energy of the oscillation about its equilibrium,
/// `E_osc = ½m|v|² + ½k|x − x*|²`, of `system`'s initial state: a bob on a
/// spring of rest length zero to a pinned anchor `a`, under gravity `g`,
/// in equilibrium at `x* = a + m g / k`.
fn oscillation_energy(system: &System) -> f64 {
    let [spring] = system.springs() else {
        panic!("the oscillator has one spring");
    };
    approx::assert_abs_diff_eq!(spring.rest_length, 0.0);
    let (anchor, bob) = if system.is_pinned(spring.i) {
        (spring.i, spring.j)
    } else {
        (spring.j, spring.i)
    };
    assert!(system.is_pinned(anchor) && !system.is_pinned(bob));
    let state = system.initial_state();
    let (x, v) = (state.positions(), state.velocities());
    let m = system.masses()[bob];
    let g = system.gravity().unwrap_or_else(Vec3::zeros);
    let equilibrium = x[anchor] + g * (m / spring.stiffness);
    0.5 * m * v[bob].norm_squared() + 0.5 * spring.stiffness * (x[bob] - equilibrium).norm_squared()
}

#[test]
fn omega_max_of_the_oscillator_is_one() {
    let report = sweep();
    assert!(
        (report.omega_max - 1.0).abs() < 1e-12,
        "{}",
        report.omega_max
    );
    for cell in &report.cells {
        let expected = cell.dt * cell.stiffness_scale.sqrt();
        assert!((cell.h_omega - expected).abs() <= 1e-12 * expected);
    }
}

#[test]
fn the_implicit_methods_are_stable_in_every_cell() {
    let report = sweep();
    for method in [Method::BackwardEuler, Method::Bdf2] {
        let cells: Vec<_> = report
            .cells
            .iter()
            .filter(|c| c.integrator == method)
            .collect();
        assert_eq!(cells.len(), 19 * 13);
        for cell in cells {
            assert!(cell.stable, "{method}: {cell:?}");
            assert!(cell.max_energy_ratio <= 1.0 + 1e-9, "{method}: {cell:?}");
        }
    }
}

#[test]
fn euler_midpoint_and_heun_gain_energy_as_their_amplification_factors_say() {
    let report = sweep();
    let bound = report.energy_bound;
    for (method, order) in [
        (ExplicitMethod::ExplicitEuler, 1),
        (ExplicitMethod::Midpoint, 2),
        (ExplicitMethod::Heun, 2),
    ] {
        let name = Method::Explicit(method).name();
        let mut dts_with_gain = std::collections::BTreeSet::new();
        for cell in report.cells.iter().filter(|c| c.integrator.name() == name) {
            let theta = cell.h_omega;
            let planned = ((0.1 / cell.dt).ceil() as usize).max(1000);
            let expected =
                expected_ratio(taylor(theta, order), cell.stiffness_scale, planned, bound);
            if expected.is_finite() && expected - 1.0 > 1e-9 && expected <= bound {
                assert!(cell.max_energy_ratio > 1.0, "{name}: {cell:?}");
                assert!(
                    (cell.max_energy_ratio - expected).abs() <= 1e-6 * expected,
                    "{name}: measured {} against {expected} at θ = {theta}",
                    cell.max_energy_ratio
                );
                assert!(cell.stable);
                dts_with_gain.insert(cell.dt.to_bits());
            }
            if expected > bound {
                assert!(!cell.stable, "{name}: {cell:?} (expected ratio {expected})");
                assert!(cell.max_energy_ratio > bound, "{name}: {cell:?}");
                dts_with_gain.insert(cell.dt.to_bits());
            }
        }
        // Every step size of the sweep shows the gain at some stiffness
        // (where theory says it exceeds rounding).
        assert_eq!(dts_with_gain.len(), 13, "{name}");
    }
}

#[test]
fn the_bounded_methods_are_stable_below_their_limit_and_not_above_it() {
    let report = sweep();
    for method in Method::ALL {
        let OscillatorStability::BoundedUpTo(limit) = method.oscillator_stability() else {
            continue;
        };
        let cells: Vec<_> = report
            .cells
            .iter()
            .filter(|c| c.integrator == method)
            .collect();
        let (mut below, mut above) = (0, 0);
        for cell in cells {
            if cell.h_omega < 0.98 * limit {
                assert!(cell.stable, "{method}: {cell:?}");
                below += 1;
            } else if cell.h_omega > 1.02 * limit {
                assert!(!cell.stable, "{method}: {cell:?}");
                above += 1;
            }
        }
        assert!(
            below > 50 && above > 20,
            "{method}: {below} below, {above} above"
        );
    }
}

#[test]
fn rk4_matches_its_amplification_factor_in_every_stable_cell() {
    let report = sweep();
    let bound = report.energy_bound;
    for cell in report
        .cells
        .iter()
        .filter(|c| c.integrator == Method::Explicit(ExplicitMethod::Rk4) && c.stable)
    {
        let planned = ((0.1 / cell.dt).ceil() as usize).max(1000);
        let expected = expected_ratio(
            taylor(cell.h_omega, 4),
            cell.stiffness_scale,
            planned,
            bound,
        );
        assert!(
            (cell.max_energy_ratio - expected).abs() <= 1e-6 * expected.max(1.0),
            "measured {} against {expected}: {cell:?}",
            cell.max_energy_ratio
        );
    }
}

#[test]
fn limit_search_finds_two_and_two_root_two() {
    let scene = builtin::load("oscillator").unwrap();
    let mut options = StabilityOptions::for_scene(&scene);
    options.scales = vec![1.0];
    options.dts = vec![1e-3, 10.0];
    options.limit_scale = Some(1.0);
    let report = stability(&scene, &options, &|_, _| {}).unwrap();
    let limits = report.limits.unwrap();
    assert_eq!(limits.len(), Method::ALL.len());
    for (method, limit) in Method::ALL.into_iter().zip(&limits) {
        assert_eq!(limit.integrator, method);
        match method.oscillator_stability() {
            OscillatorStability::BoundedUpTo(theory) => {
                let found = limit.h_omega_limit.unwrap();
                assert!(
                    (found / theory - 1.0).abs() < 0.02,
                    "{method}: h·ω limit {found}, theory {theory}"
                );
            }
            OscillatorStability::Unconditional => {
                assert_eq!(limit.max_stable_dt, None, "{method}");
                // Searched up to h·ω = 1000 (ω = 1 rad/s).
                assert!((limit.searched_up_to - 1e3).abs() < 1e-9, "{method}");
            }
            OscillatorStability::GainsEnergy => {
                // A finite run stays under the bound while the energy has
                // not grown tenfold: well below any bounded method's limit.
                let found = limit.h_omega_limit.unwrap();
                assert!(found < 1.2, "{method}: {found}");
            }
        }
    }
}

/// The energy budget adds no error of its own: with gravity's work exact,
/// at small steps (`h·ω` from 10⁻³ to 2·10⁻², 1000 steps) the ratio the
/// sweep reports is the amplification factor's to 10⁻⁹ relative, in the
/// cells where theory's `max ratio − 1` exceeds 10⁻⁸ (midpoint and Heun
/// gain `E_osc ((1 + θ⁴/4)ⁿ − 1) = 2.6·10⁻⁵ E_osc` at `θ = 0.018`, with
/// `E_osc = ½` J: a ratio of `1 + 2.9·10⁻⁶` against the allowance of 4.5 J
/// the bob's lowest point sets) and in every other cell too (RK4 loses
/// energy at these steps: its ratio stays just below one).
#[test]
fn the_reported_ratio_is_the_amplification_factors_at_small_steps() {
    let scene = builtin::load("oscillator").unwrap();
    let mut options = StabilityOptions::for_scene(&scene);
    let methods = [
        (ExplicitMethod::ExplicitEuler, 1),
        (ExplicitMethod::Midpoint, 2),
        (ExplicitMethod::Heun, 2),
        (ExplicitMethod::Rk4, 4),
    ];
    options.methods = methods.iter().map(|&(m, _)| Method::Explicit(m)).collect();
    options.scales = vec![1.0];
    options.dts = hooke_lab::Range::new(1e-3, 2e-2, 9).values();
    options.dts.push(0.018);
    options.duration = 1.0;
    let report = stability(&scene, &options, &|_, _| {}).unwrap();
    assert_eq!(report.cells.len(), 4 * 10);
    let mut gaining = 0;
    for (method, order) in methods {
        let name = Method::Explicit(method).name();
        for cell in report.cells.iter().filter(|c| c.integrator.name() == name) {
            assert_eq!(cell.steps, 1000, "{cell:?}");
            let expected = expected_ratio(taylor(cell.h_omega, order), 1.0, 1000, f64::INFINITY);
            if expected - 1.0 > 1e-8 {
                gaining += 1;
            }
            assert!(
                (cell.max_energy_ratio - expected).abs() <= 1e-9 * expected,
                "{name} at θ = {}: reported {} against {expected}",
                cell.h_omega,
                cell.max_energy_ratio
            );
        }
    }
    // Explicit Euler in every cell, midpoint and Heun from θ = 0.0045 on.
    assert_eq!(gaining, 10 + 2 * 6, "cells that gain more than 1e-8");
}

/// The gain in joules the default sweep reports is theory's at every
/// stiffness scale. On the oscillator the gain `E − E(0) − W` is the
/// change of the oscillation's energy about its equilibrium, `E_osc`, and
/// each step multiplies that by `|R(iθ)|²`: after the `n` steps a cell
/// took, `G = E_osc ((1 + θ²)ⁿ − 1)` for explicit Euler and
/// `E_osc ((1 + θ⁴/4)ⁿ − 1)` for midpoint and Heun. The reported gain
/// matches to 1 % wherever theory's exceeds `10⁻⁹ E_osc`, and stays below
/// `2·10⁻⁹ E_osc` (rounding) elsewhere. Among the cells: midpoint at
/// stiffness scale 10^½ and `dt = 0.01` s (`θ = 0.0178`, 1000 steps), where
/// `G = 2.5·10⁻⁵ E_osc` while the bob is above its lowest point.
#[test]
fn the_reported_gain_is_the_theorys_at_every_stiffness() {
    let scene = builtin::load("oscillator").unwrap();
    let mut options = StabilityOptions::for_scene(&scene);
    let methods = [
        ExplicitMethod::ExplicitEuler,
        ExplicitMethod::Midpoint,
        ExplicitMethod::Heun,
    ];
    options.methods = methods.map(Method::Explicit).to_vec();
    let report = stability(&scene, &options, &|_, _| {}).unwrap();
    assert_eq!(report.cells.len(), 3 * 19 * 13);
    for method in methods {
        let name = Method::Explicit(method).name();
        let mut scales_gaining = std::collections::BTreeSet::new();
        for cell in report.cells.iter().filter(|c| c.integrator.name() == name) {
            let system = scene
                .system
                .with_stiffness_scale(cell.stiffness_scale)
                .unwrap();
            let e_osc = oscillation_energy(&system);
            let theta = cell.h_omega;
            // |R|² − 1 per step.
            let growth = match method {
                ExplicitMethod::ExplicitEuler => theta * theta,
                _ => theta.powi(4) / 4.0,
            };
            let planned = ((options.duration / cell.dt).ceil() as usize).max(options.min_steps);
            assert!(cell.steps == planned || !cell.stable, "{name}: {cell:?}");
            let n = cell.steps as f64;
            let expected = e_osc * (n * growth.ln_1p()).exp_m1();
            let gain = cell.max_energy_gain;
            if expected > 1e-9 * e_osc {
                assert!(
                    (gain - expected).abs() <= 0.01 * expected,
                    "{name} at scale {}, θ = {theta}, {} steps: gain {gain} J, theory {expected} J",
                    cell.stiffness_scale,
                    cell.steps
                );
                scales_gaining.insert(cell.stiffness_scale.to_bits());
            } else {
                assert!(
                    gain <= 2e-9 * e_osc,
                    "{name} at scale {}, θ = {theta}: gain {gain} J of E_osc = {e_osc} J, theory {expected} J",
                    cell.stiffness_scale
                );
            }
        }
        assert_eq!(scales_gaining.len(), 19, "{name}");
    }
}
