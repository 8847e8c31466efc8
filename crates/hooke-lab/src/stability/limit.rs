//! Each method's largest stable step, by doubling then bisection.

#[cfg(feature = "parallel")]
use rayon::prelude::*;

use hooke_scenes::Scene;

use super::cell::{cell_steps, run_cell};
use super::{Limit, StabilityOptions};
use crate::surfaces::{Systems, Target};
use crate::{LabError, Method};

/// Relative width at which the bisection stops.
const LIMIT_PRECISION: f64 = 1e-4;

/// The largest `h·ω_max` the limit search tries.
pub const LIMIT_SEARCH_H_OMEGA: f64 = 1e3;

/// Each method's largest stable step at stiffness `scale`: from the
/// smallest of `options.dts` the step doubles until a run is unstable (or
/// passes both the largest of `options.dts` and `h·ω_max =`
/// [`LIMIT_SEARCH_H_OMEGA`]), then a geometric bisection narrows the
/// bracket to a relative width of 10⁻⁴. The search assumes that stability
/// is lost once, at one step; the methods run in parallel. Methods that
/// cannot run the scene (see [`Systems::target`]) are left out.
pub(super) fn limits(
    scene: &Scene,
    options: &StabilityOptions,
    scale: f64,
    omega_max: f64,
) -> Result<Vec<Limit>, LabError> {
    let systems = Systems::new(scene.system.with_stiffness_scale(scale)?);
    let lowest = options.dts.iter().copied().fold(f64::INFINITY, f64::min);
    let omega = omega_max * scale.sqrt();
    let mut highest = options.dts.iter().copied().fold(0.0, f64::max);
    if omega > 0.0 {
        highest = highest.max(LIMIT_SEARCH_H_OMEGA / omega);
    }
    let stable_at = |method: Method, dt: f64| -> Result<bool, LabError> {
        let Target::Runs(system) = systems.target(method) else {
            return Ok(false);
        };
        let steps = cell_steps(options.duration, options.min_steps, dt);
        Ok(run_cell(
            system,
            method,
            &options.settings,
            dt,
            steps,
            options.energy_bound,
        )?
        .stable)
    };
    let search = |&method: &Method| -> Result<Limit, LabError> {
        let mut limit = Limit {
            integrator: method,
            stiffness_scale: scale,
            max_stable_dt: None,
            h_omega_limit: None,
            searched_up_to: lowest,
            searched_down_to: lowest,
        };
        if !stable_at(method, lowest)? {
            return Ok(limit);
        }
        let (mut lo, mut hi) = (lowest, None);
        while lo < highest {
            let next = (2.0 * lo).min(highest);
            limit.searched_up_to = next;
            if stable_at(method, next)? {
                lo = next;
            } else {
                hi = Some(next);
                break;
            }
        }
        if let Some(mut hi) = hi {
            while hi / lo > 1.0 + LIMIT_PRECISION {
                let mid = (lo * hi).sqrt();
                if stable_at(method, mid)? {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            limit.max_stable_dt = Some(lo);
            limit.h_omega_limit = Some(lo * omega);
        }
        Ok(limit)
    };
    let applicable: Vec<Method> = options
        .methods
        .iter()
        .copied()
        .filter(|&m| matches!(systems.target(m), Target::Runs(_)))
        .collect();
    let methods = match options.shard {
        Some(shard) => shard.deal(&applicable),
        None => applicable,
    };
    #[cfg(feature = "parallel")]
    let found = methods.par_iter().map(search).collect();
    #[cfg(not(feature = "parallel"))]
    let found = methods.iter().map(search).collect();
    found
}
