//! Combining the partial reports of a sharded sweep
//! ([`StabilityOptions::shard`](crate::StabilityOptions::shard),
//! [`AccuracyOptions::shard`](crate::AccuracyOptions::shard)) into the
//! report an unsharded run writes: [`StabilityReport::merge`] and
//! [`AccuracyReport::merge`].
//!
//! Part `i` of `N` ran the jobs numbered `k ≡ i (mod N)`, so the merged
//! report's cells, runs and limits are the parts' interleaved back in
//! order ([`interleave`]); an accuracy merge then marks the runs the
//! reference resolves and fits the orders over all of them, as the
//! unsharded measurement does. Every value but the wall times is what the
//! unsharded run computes: the jobs are independent and deterministic.

use crate::accuracy::conclude;
use crate::{AccuracyReport, LabError, Shard, StabilityReport, interleave};

/// Checks that `parts` are the `N` parts of one sharding, each once, and
/// sorts them by index.
fn order_parts<R>(parts: &mut [R], shard: impl Fn(&R) -> Option<Shard>) -> Result<(), LabError> {
    let fail = |reason: String| Err(LabError::Merge { reason });
    let Some(first) = parts.first() else {
        return fail("no partial reports".to_owned());
    };
    let Some(Shard { count, .. }) = shard(first) else {
        return fail("a report is not partial (it has no shard)".to_owned());
    };
    let mut indices = Vec::with_capacity(parts.len());
    for part in parts.iter() {
        match shard(part) {
            Some(s) if s.count == count => indices.push(s.index),
            Some(s) => return fail(format!("shard {s} beside shards of {count}")),
            None => return fail("a report is not partial (it has no shard)".to_owned()),
        }
    }
    indices.sort_unstable();
    if indices != (0..count).collect::<Vec<_>>() {
        return fail(format!(
            "shards {indices:?} of {count}: each of 0..{count} once"
        ));
    }
    parts.sort_by_key(|p| shard(p).map_or(0, |s| s.index));
    Ok(())
}

/// `Ok` if every part says the same of `what` as the first.
fn agree<R, T: PartialEq>(
    parts: &[R],
    what: &str,
    value: impl Fn(&R) -> T,
) -> Result<(), LabError> {
    let first = value(&parts[0]);
    if parts.iter().all(|p| value(p) == first) {
        Ok(())
    } else {
        Err(LabError::Merge {
            reason: format!("the parts differ in {what}: not one sweep"),
        })
    }
}

/// The parts' items interleaved back into job order.
fn combine<R, T>(parts: &mut [R], items: impl Fn(&mut R) -> Vec<T>) -> Result<Vec<T>, LabError> {
    interleave(parts.iter_mut().map(items).collect()).ok_or_else(|| LabError::Merge {
        reason: "the parts' sizes are not those of one dealing of the jobs".to_owned(),
    })
}

impl StabilityReport {
    /// The report of the whole sweep from the reports of its `N` parts.
    ///
    /// # Errors
    /// [`LabError::Merge`] if the reports are not the `N` parts of one
    /// sweep, each once.
    pub fn merge(mut parts: Vec<Self>) -> Result<Self, LabError> {
        order_parts(&mut parts, |p| p.shard)?;
        agree(&parts, "scene", |p| p.scene.clone())?;
        agree(&parts, "energy bound, duration and steps", |p| {
            (p.energy_bound, p.duration, p.min_steps)
        })?;
        agree(&parts, "methods, stiffness scales and steps", |p| {
            (p.methods.clone(), p.stiffness_scales.clone(), p.dts.clone())
        })?;
        agree(&parts, "ω_max", |p| (p.omega_max, p.omega_max_bound))?;
        agree(&parts, "limit search", |p| p.limits.is_some())?;
        agree(&parts, "note", |p| p.note.clone())?;
        let cells = combine(&mut parts, |p| std::mem::take(&mut p.cells))?;
        let limits = if parts[0].limits.is_some() {
            Some(combine(&mut parts, |p| {
                p.limits.take().unwrap_or_default()
            })?)
        } else {
            None
        };
        let mut merged = parts.swap_remove(0);
        merged.cells = cells;
        merged.limits = limits;
        merged.shard = None;
        Ok(merged)
    }
}

impl AccuracyReport {
    /// The report of the whole measurement from the reports of its `N`
    /// parts, with the runs the reference resolves marked and the orders
    /// fitted over all runs.
    ///
    /// # Errors
    /// [`LabError::Merge`] if the reports are not the `N` parts of one
    /// measurement, each once.
    pub fn merge(mut parts: Vec<Self>) -> Result<Self, LabError> {
        order_parts(&mut parts, |p| p.shard)?;
        agree(&parts, "scene", |p| p.scene.clone())?;
        agree(&parts, "duration, frames and repeats", |p| {
            (p.duration, p.frames, p.repeat)
        })?;
        agree(&parts, "methods, steps and tolerances", |p| {
            (p.methods.clone(), p.dts.clone(), p.tolerances.clone())
        })?;
        agree(&parts, "ω_max and the motion's scales", |p| {
            (p.omega_max, p.motion_scale, p.position_scale)
        })?;
        agree(&parts, "note", |p| p.note.clone())?;
        agree(&parts, "reference", |p| {
            let r = &p.reference;
            (
                r.kind,
                r.method.clone(),
                r.dt,
                r.estimated_error,
                r.observed_order,
            )
        })?;
        let runs = combine(&mut parts, |p| std::mem::take(&mut p.runs))?;
        let mut merged = parts.swap_remove(0);
        merged.runs = runs;
        merged.shard = None;
        conclude(&mut merged);
        Ok(merged)
    }
}
