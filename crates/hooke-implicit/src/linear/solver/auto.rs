//! [`LinearSolver::Auto`]'s trial.

use std::time::{Duration, Instant};

use hooke_core::{StepError, System, Vec3};

use super::LinearSolver;
use super::auto_settings::AutoSettings;
use super::topology::Topology;
use crate::linear::amg::{Amg, AmgError, AmgSettings};
use crate::linear::cg::{self, PcgSettings, PcgWorkspace};
use crate::linear::cholesky::{
    CholeskyError, FillOrdering, Routes, SparseCholesky, predicted_factor_entries,
};

/// [`LinearSolver::Auto`]'s trial: solves the filtered system last
/// assembled, `S A y = S r`, for a right-hand side `r` of pseudo-random
/// components in `[−1, 1]` with each candidate ([`second_run`] timing
/// it), keeps what the chosen one built (the factor or the hierarchy) and
/// returns it — the fastest, but an iterative candidate only within
/// [`auto.iterative_margin`](AutoSettings::iterative_margin) of the
/// factorization's time —, whether it falls back to the factorization (an
/// iterative choice where the factor is affordable) and, when the
/// factorization and the fastest iterative candidate are within
/// [`auto.probe_ratio`](AutoSettings::probe_ratio), the comparison of the
/// two on whole steps (the runner-up), for which it keeps what both built. A
/// right-hand side of every frequency tries each preconditioner as
/// the later Newton systems will, where the step's own one may be smooth
/// (a cloth at rest under gravity) and flatter a preconditioner that only
/// damps smooth errors.
///
/// # Errors
/// [`StepError::NotPositiveDefinite`] when the factorization, or multigrid
/// where the factor is not tried, finds the matrix not positive definite;
/// the next solve tries again.
pub(super) fn trial(
    topology: &mut Topology,
    system: &System,
    positions: &[Vec3],
    workspace: &mut PcgWorkspace,
    time: f64,
) -> Result<(LinearSolver, bool, Option<LinearSolver>), StepError> {
    let auto = AutoSettings::DEFAULT;
    let Topology {
        matrix,
        jacobi,
        filters,
        cholesky,
        amg,
        factoring: (weak_springs, supernodes),
        ..
    } = topology;
    // xorshift64*, mapped to [−1, 1].
    let mut seed = 0x9E37_79B9_7F4A_7C15_u64;
    let mut uniform = || {
        seed ^= seed >> 12;
        seed ^= seed << 25;
        seed ^= seed >> 27;
        (seed.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    };
    let r: Vec<Vec3> = filters
        .iter()
        .map(|f| f.apply(Vec3::new(uniform(), uniform(), uniform())))
        .collect();
    let mut y = vec![Vec3::zeros(); r.len()];
    // The factorization's time, and the iterative candidates' times.
    let mut direct = None;
    let mut iterative: Vec<(LinearSolver, Duration)> = Vec::with_capacity(2);
    let settings = PcgSettings::default();
    let routes = Routes::of(system, matrix.pattern(), *weak_springs);
    let affordable = predicted_factor_entries(matrix.pattern(), &routes)
        .is_some_and(|entries| entries.saturating_mul(size_of::<f64>()) <= auto.factor_bytes);
    if affordable {
        // Kept for a retry when this matrix is not positive definite.
        let factor = match cholesky {
            Some(factor) => factor,
            None => cholesky.insert(SparseCholesky::with_routes(
                matrix,
                (FillOrdering::default(), *supernodes),
                routes,
            )?),
        };
        // A factor above the whole matrix (weak springs routed) is timed
        // with the CG it preconditions, to the iterative candidates'
        // tolerance: at its cap or not, that is what a solve spends.
        let ((), elapsed) = second_run(|| {
            factor.factorize(matrix, filters)?;
            factor.solve_filtered((matrix, filters), &r, &mut y, settings, workspace);
            Ok(())
        })
        .map_err(|e: CholeskyError| e.at(time))?;
        direct = Some(elapsed);
    }
    match Amg::build(matrix, filters, positions, AmgSettings::default()) {
        Ok(mut hierarchy) => {
            let solved = second_run(|| {
                hierarchy
                    .refresh_smoother(matrix, filters)
                    .map_err(|_| ())?;
                y.fill(Vec3::zeros());
                let cycle = hierarchy.cycle(matrix, filters);
                cg::solve(matrix, &cycle, filters, &r, &mut y, settings, workspace).map_err(|_| ())
            });
            if let Ok((_, elapsed)) = solved {
                iterative.push((LinearSolver::Amg(settings), elapsed));
                // The first solve of the step's own systems sets the
                // baseline of the renewals: the pseudo-random right-hand
                // side takes more iterations than they do.
                amg.clear();
                amg.amg = Some(hierarchy);
            }
        }
        Err(AmgError::NotPositiveDefinite(particle)) if !affordable => {
            return Err(StepError::NotPositiveDefinite {
                time,
                particle: Some(particle),
            });
        }
        Err(_) => {}
    }
    let capped = PcgSettings::new(settings.tolerance(), auto.trial_pcg_iterations)
        .expect("a tolerance in (0, 1) and a positive cap");
    let solved = second_run(|| {
        y.fill(Vec3::zeros());
        cg::solve(matrix, jacobi, filters, &r, &mut y, capped, workspace)
    });
    if let Ok((_, elapsed)) = solved {
        iterative.push((LinearSolver::Pcg(settings), elapsed));
    }
    // An iterative candidate must beat the factorization by the margin;
    // with nothing solved, multigrid — the candidate for systems too large
    // to factorize — reports why at the solve that follows.
    let fastest = iterative
        .iter()
        .min_by_key(|&&(_, elapsed)| elapsed)
        .copied();
    let best = match (fastest, direct) {
        (Some((choice, elapsed)), Some(direct))
            if elapsed.as_secs_f64() <= auto.iterative_margin * direct.as_secs_f64() =>
        {
            choice
        }
        (_, Some(_)) => LinearSolver::Cholesky,
        (Some((choice, _)), None) => choice,
        (None, None) => LinearSolver::Amg(settings),
    };
    // The factorization and the fastest iterative candidate close enough
    // to compare on whole steps.
    let probe = match (fastest, direct) {
        (Some((choice, elapsed)), Some(direct)) => {
            let (iterative, direct) = (elapsed.as_secs_f64(), direct.as_secs_f64());
            (iterative.max(direct) <= auto.probe_ratio * iterative.min(direct)).then(|| {
                if best == LinearSolver::Cholesky {
                    choice
                } else {
                    LinearSolver::Cholesky
                }
            })
        }
        _ => None,
    };
    // Multigrid as the other candidate is built at its first solve, as in
    // a run that starts with it: the trial's hierarchy, kept idle through
    // the factorization's step, set off other refreshes and rebuilds, and
    // steps of the 200² swinging cloth took 4.3–8.2 s against 4.7 s.
    if best != LinearSolver::Cholesky && probe.is_none() {
        *cholesky = None;
    }
    if !matches!(best, LinearSolver::Amg(_)) {
        amg.clear();
    }
    Ok((best, affordable && best != LinearSolver::Cholesky, probe))
}

/// Runs `solve` twice and times the second run, which finds in place the
/// memory the first touched (a fresh factor, a fresh hierarchy), as the
/// solves of a run do; a failing first run is returned as is.
fn second_run<T, E>(mut solve: impl FnMut() -> Result<T, E>) -> Result<(T, Duration), E> {
    solve()?;
    let clock = Instant::now();
    let out = solve()?;
    Ok((out, clock.elapsed()))
}
