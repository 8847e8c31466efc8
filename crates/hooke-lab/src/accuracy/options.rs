//! [`AccuracyOptions`]: what an accuracy measurement runs.

use hooke_scenes::Scene;

use super::StepVariant;
use crate::spectrum::omega_max;
use crate::{LabError, Method, Range, Settings, Shard};

/// Where the reference comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReferenceChoice {
    /// The closed form where the scene has one, else numerical.
    Auto,
    /// Always the numerical reference.
    Numerical,
}

/// What to measure.
#[derive(Debug, Clone, PartialEq)]
pub struct AccuracyOptions {
    /// The methods, in report order.
    pub methods: Vec<Method>,
    /// Requested steps of the fixed-step methods, s.
    pub dts: Vec<f64>,
    /// Tolerances of the adaptive method.
    pub tolerances: Vec<f64>,
    /// Simulated time, s.
    pub duration: f64,
    /// Checkpoints ("written frames"), evenly spaced, the last at `duration`.
    pub frames: usize,
    /// Timed repeats of each run.
    pub repeat: usize,
    /// The methods' parameters.
    pub settings: Settings,
    /// Where the reference comes from.
    pub reference: ReferenceChoice,
    /// The numerical reference's step, s (`None`: `min(0.5/ω_max, dt_min/4)`).
    pub reference_dt: Option<f64>,
    /// Run only this part of the runs (every part computes the
    /// reference): the report is then partial, for [`merge`](crate::merge).
    /// Part 0 runs the step variants.
    pub shard: Option<Shard>,
    /// Backward Euler's step variants to compare with its tightly
    /// converged step (see the `variants` module).
    pub variants: Vec<StepVariant>,
    /// The steps at which the variants run, s.
    pub variant_dts: Vec<f64>,
}

impl AccuracyOptions {
    /// Every method; 13 steps over three decades up to
    /// `dt_max = max(scene dt, 0.5/ω_max)` (the scene's own step for the
    /// implicit methods, the explicit methods well resolved at the small
    /// end); tolerances 10⁻³…10⁻⁹; the scene's duration; 10 frames; 3
    /// repeats; the scene's implicit and adaptive parameters; the automatic
    /// reference; no step variants, to be run at the scene's step.
    #[must_use]
    pub fn for_scene(scene: &Scene) -> Self {
        let omega = omega_max(&scene.system).omega_max;
        let mut largest = scene.timing.dt;
        if omega > 0.0 {
            largest = largest.max(0.5 / omega);
        }
        Self {
            methods: Method::ALL.to_vec(),
            dts: Range::new(largest / 1000.0, largest, 13).values(),
            tolerances: Range::new(1e-3, 1e-9, 7).values(),
            duration: scene.timing.duration,
            frames: 10,
            repeat: 3,
            settings: Settings::from_scene(&scene.integrator),
            reference: ReferenceChoice::Auto,
            reference_dt: None,
            shard: None,
            variants: Vec::new(),
            variant_dts: vec![scene.timing.dt],
        }
    }

    pub(super) fn check(&self) -> Result<(), LabError> {
        let (positive, at_least_one) = (LabError::positive, LabError::at_least_one);
        at_least_one("methods", self.methods.len())?;
        if self.methods.iter().any(|m| m.is_fixed_step()) {
            at_least_one("dt values", self.dts.len())?;
        }
        if self.methods.contains(&Method::DormandPrince) {
            at_least_one("tolerances", self.tolerances.len())?;
        }
        self.dts.iter().try_for_each(|&dt| positive("dt", dt))?;
        self.tolerances
            .iter()
            .try_for_each(|&t| positive("tolerance", t))?;
        positive("duration", self.duration)?;
        at_least_one("frames", self.frames)?;
        at_least_one("repeat", self.repeat)?;
        if !self.variants.is_empty() {
            at_least_one("variant steps", self.variant_dts.len())?;
        }
        self.variant_dts
            .iter()
            .try_for_each(|&dt| positive("variant dt", dt))?;
        self.reference_dt
            .map_or(Ok(()), |dt| positive("reference dt", dt))
    }
}
