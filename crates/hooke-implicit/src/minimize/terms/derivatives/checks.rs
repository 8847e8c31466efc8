//! The checks on one term at a case's point: its gradient, its Hessian,
//! its clamped Hessian and its right-hand side at a linearisation.

use hooke_core::{CompressedSprings, Term, Vec3};
use nalgebra::DMatrix;

use super::dense::{RATIOS, largest, parts, positive_part, smallest_eigenvalue};
use super::kinds::Curvature;
use super::point::{Point, flat, largest_of};

/// The relative error allowed a gradient against its central
/// differences, and a Hessian against its gradient's.
const GRADIENT_TOLERANCE: f64 = 1e-6;
const HESSIAN_TOLERANCE: f64 = 1e-5;

/// The smallest eigenvalue allowed a positive-semidefinite Hessian,
/// relative to its norm: rounding.
const DEFINITE_TOLERANCE: f64 = 1e-10;

const AXES: [char; 3] = ['x', 'y', 'z'];

/// The term's gradient, by each of its ways, against the central
/// differences of its value.
pub(super) fn gradient(term: &mut dyn Term, point: &Point) -> Result<(), String> {
    let system = &point.case.system;
    let s = point.beta_h;
    let value = point.value(term, s, None);
    let mut magnitude = value.magnitude;
    let numeric: Vec<f64> = (0..3 * point.particles())
        .map(|k| {
            point.difference(s, k, |by| {
                let p = point.value(term, s, Some(by));
                magnitude = magnitude.max(p.magnitude);
                vec![p.value]
            })[0]
        })
        .collect();
    let mut ways = Vec::new();
    for compressed in [CompressedSprings::Exact, CompressedSprings::Clamped] {
        let b = point.add(term, s, None, (compressed, None)).0;
        ways.push((format!("`add` ({compressed:?})"), flat(&b)));
    }
    let mut b = vec![Vec3::zeros(); point.particles()];
    let how = (CompressedSprings::Exact, None);
    let both = point.at(s, None, how, |at| term.gradient(system, at, &mut b));
    if (both.value - value.value).abs() > 4.0 * value.rounding()
        || (both.magnitude - value.magnitude).abs() > 1e-12 * value.magnitude
    {
        return Err(format!(
            "`gradient` gives {both:?}, `value` {value:?} at the point"
        ));
    }
    ways.push(("`gradient`".to_owned(), flat(&b)));
    let rounding = point.rounding(s, magnitude);
    for (way, analytic) in &ways {
        let tolerance = (GRADIENT_TOLERANCE + point.coordinate_rounding)
            * largest_of(numeric.iter().chain(analytic))
            + rounding;
        for (k, (d, a)) in numeric.iter().zip(analytic).enumerate() {
            if (d - a).abs() > tolerance {
                return Err(format!(
                    "∂Φ/∂v at {} is {d:.9e} by central differences of the value (steps \
                     {:.1e} m, {:.1e} m/s), {a:.9e} by {way} (tolerance {tolerance:.1e})",
                    coordinate(k),
                    point.dx,
                    point.dv
                ));
            }
        }
    }
    Ok(())
}

/// The central differences of the term's gradient at `βh` = `s`, column
/// `k` the difference of `∇Φ` along coordinate `k`, and the error the
/// rounding of the gradient may put into them.
fn differences(term: &mut dyn Term, point: &Point, s: f64) -> (DMatrix<f64>, f64) {
    let how = (CompressedSprings::Exact, None);
    let size = 3 * point.particles();
    let mut hessian = DMatrix::zeros(size, size);
    let mut gradient = 0.0_f64;
    for k in 0..size {
        let column = point.difference(s, k, |by| {
            let g = flat(&point.add(term, s, Some(by), how).0);
            gradient = gradient.max(largest_of(&g));
            g
        });
        hessian.set_column(k, &nalgebra::DVector::from_vec(column));
    }
    (hessian, 16.0 * point.rounding(s, gradient))
}

/// Coordinate `k` of the velocities, by particle and axis.
fn coordinate(k: usize) -> String {
    format!("particle {}'s {}", k / 3, AXES[k % 3])
}

/// `written` is `exact` within `tolerance`, entry by entry.
fn compare(
    what: &str,
    written: &DMatrix<f64>,
    exact: &DMatrix<f64>,
    tolerance: f64,
) -> Result<(), String> {
    let (row, column) = (written - exact).iamax_full();
    let (w, e) = (written[(row, column)], exact[(row, column)]);
    if (w - e).abs() > tolerance {
        return Err(format!(
            "{what}: its entry at ({}, {}) is {w:.9e} as written, {e:.9e} by central \
             differences of the gradient (tolerance {tolerance:.1e})",
            coordinate(row),
            coordinate(column)
        ));
    }
    Ok(())
}

/// `written − exact` is positive semidefinite within `tolerance`.
fn above(
    what: &str,
    written: &DMatrix<f64>,
    exact: &DMatrix<f64>,
    tolerance: f64,
) -> Result<(), String> {
    let (lowest, particle) = smallest_eigenvalue(&(written - exact));
    if lowest < -tolerance {
        return Err(format!(
            "{what}: as written it lies below the central differences of the gradient, by an \
             eigenvalue {lowest:.6e} whose vector lies mostly on particle {particle} \
             (tolerance {tolerance:.1e})"
        ));
    }
    Ok(())
}

/// The parts of a Hessian by the powers of `βh`.
const PARTS: [&str; 3] = [
    "the Hessian's part in (βh)⁰, the inertia's",
    "the Hessian's part in βh, the dissipation potentials'",
    "the Hessian's part in β²h², the potentials'",
];

/// The Hessian the term writes with exact Hessians against the central
/// differences of its gradient (a barrier's by parts, its potentials' as
/// the case's [`Curvature`] says), and, after a failed full step, above
/// them. Returns a barrier's largest entries of its dissipation
/// potentials' and its potentials' parts relative to its Hessian's (zeros
/// for another term).
pub(super) fn hessian(term: &mut dyn Term, point: &Point) -> Result<[f64; 2], String> {
    let how = (CompressedSprings::Exact, None);
    let barrier = term.is_barrier();
    let ratios: &[f64] = if barrier { &RATIOS } else { &[1.0] };
    let (mut written, mut numeric) = (Vec::new(), Vec::new());
    let (mut scale, mut rounding) = (0.0_f64, 0.0_f64);
    for &r in ratios {
        let s = r * point.beta_h;
        let w = point.add(term, s, None, how).1;
        let (f, error) = differences(term, point, s);
        scale = scale.max(largest(&w)).max(largest(&f));
        rounding = rounding.max(error);
        written.push(w);
        numeric.push(f);
    }
    let tolerance = (HESSIAN_TOLERANCE + point.coordinate_rounding) * scale + rounding;
    let split = |samples: &[DMatrix<f64>]| parts(samples.try_into().expect("three samples"));
    let mut reached = [0.0; 2];
    if barrier {
        let (w, f) = (split(&written), split(&numeric));
        reached = [largest(&w[1].0) / scale, largest(&w[2].0) / scale];
        for k in 0..2 {
            compare(PARTS[k], &w[k].0, &f[k].0, w[k].1 * tolerance)?;
        }
        let ((w, magnified), f) = (&w[2], &f[2].0);
        let tolerance = magnified * tolerance;
        match point.case.curvature {
            Curvature::Exact => compare(PARTS[2], w, f, tolerance)?,
            Curvature::Positive => compare(PARTS[2], w, &positive_part(f), tolerance)?,
            Curvature::Above => above(PARTS[2], w, f, tolerance)?,
        }
    } else {
        compare("the Hessian", &written[0], &numeric[0], tolerance)?;
    }
    term.full_step_failed();
    let again: Vec<_> = ratios
        .iter()
        .map(|r| point.add(term, r * point.beta_h, None, how).1)
        .collect();
    let failed = "after a failed full step";
    if barrier {
        let (w, f) = (split(&again), split(&numeric));
        for k in 0..3 {
            above(
                &format!("{failed}, {}", PARTS[k]),
                &w[k].0,
                &f[k].0,
                w[k].1 * tolerance,
            )?;
        }
    } else {
        above(
            &format!("{failed}, the Hessian"),
            &again[0],
            &numeric[0],
            tolerance,
        )?;
    }
    Ok(reached)
}

/// The Hessian the term writes with clamped Hessians is positive
/// semidefinite.
pub(super) fn definite(term: &mut dyn Term, point: &Point) -> Result<(), String> {
    let how = (CompressedSprings::Clamped, None);
    let w = point.add(term, point.beta_h, None, how).1;
    let (lowest, particle) = smallest_eigenvalue(&w);
    let tolerance = DEFINITE_TOLERANCE * w.norm();
    if lowest < -tolerance {
        return Err(format!(
            "its clamped Hessian has the eigenvalue {lowest:.6e} (norm {:.3e}), its vector \
             mostly on particle {particle}",
            w.norm()
        ));
    }
    Ok(())
}

/// At a linearisation with displacement `u`, in either mode, the
/// right-hand side gains `−βh K u`, `β²h² K` the potentials' part of the
/// Hessian written there.
pub(super) fn linearisation(term: &mut dyn Term, point: &Point) -> Result<(), String> {
    let (case, beta_h) = (point.case, point.beta_h);
    let u: Vec<Vec3> = (case.v_tilde.iter().zip(&case.v))
        .map(|(vt, v)| beta_h * (vt - v))
        .collect();
    let u_flat: Vec<f64> = u.iter().flat_map(|u| u.iter().copied()).collect();
    let u_sum: f64 = u_flat.iter().map(|c| c.abs()).sum();
    for compressed in [CompressedSprings::Exact, CompressedSprings::Clamped] {
        let b = flat(&point.add(term, beta_h, None, (compressed, None)).0);
        let linear = (compressed, Some(&u[..]));
        let lin = flat(&point.add(term, beta_h, None, linear).0);
        let samples = RATIOS.map(|r| point.add(term, r * beta_h, None, linear).1);
        let sampled = samples.iter().map(largest).fold(0.0, f64::max);
        let [_, _, (k, magnified)] = parts(&samples);
        // −b gains βh K u = K_part u / βh.
        let gained = &k * DMatrix::from_column_slice(u_flat.len(), 1, &u_flat) / beta_h;
        let scale = largest_of(b.iter().chain(&lin).chain(gained.iter()));
        let tolerance = 1e-9 * scale + 64.0 * f64::EPSILON * magnified * sampled * u_sum / beta_h;
        for (i, ((l, b), g)) in lin.iter().zip(&b).zip(gained.iter()).enumerate() {
            if (l - b - g).abs() > tolerance {
                return Err(format!(
                    "at a linearisation ({compressed:?}), −b at {} gains {:.9e}, where βh K u \
                     is {g:.9e} (tolerance {tolerance:.1e})",
                    coordinate(i),
                    l - b
                ));
            }
        }
    }
    Ok(())
}
