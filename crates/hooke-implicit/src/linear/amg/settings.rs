//! [`AmgSettings`]: the parameters of the hierarchy and the cycle.

use hooke_core::{Parameter, ParameterError};

use super::prolongation::MODES;

/// Parameters of the multigrid hierarchy and cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AmgSettings {
    strength: f64,
    filter: f64,
    fine_degree: usize,
    coarse_degree: usize,
    coarse_unknowns: usize,
}

impl AmgSettings {
    /// Strength threshold `θ` in `[0, 1)` of the aggregation, threshold
    /// `θ_F` in `[0, 1)` of the filtered matrix that smooths the finest
    /// prolongator, Chebyshev degree of each smoothing sweep on every level
    /// (at least 1; [`AmgSettings::with_fine_degree`] sets the finest
    /// level's apart) and the size of the coarsest level (at least 6
    /// unknowns).
    ///
    /// # Errors
    /// [`ParameterError`] for a value outside those ranges.
    pub fn new(
        strength: f64,
        filter: f64,
        smoother_degree: usize,
        coarse_unknowns: usize,
    ) -> Result<Self, ParameterError> {
        for (name, value) in [(Parameter::Strength, strength), (Parameter::Filter, filter)] {
            if !(0.0..1.0).contains(&value) {
                return Err(ParameterError::new("amg", name, value, "in [0, 1)"));
            }
        }
        check_degree(Parameter::SmootherDegree, smoother_degree)?;
        if coarse_unknowns < MODES {
            return Err(ParameterError::new(
                "amg",
                Parameter::CoarseUnknowns,
                coarse_unknowns as f64,
                "at least 6",
            ));
        }
        Ok(Self {
            strength,
            filter,
            fine_degree: smoother_degree,
            coarse_degree: smoother_degree,
            coarse_unknowns,
        })
    }

    /// The same settings with Chebyshev sweeps of `degree` on the finest
    /// level.
    ///
    /// # Errors
    /// [`ParameterError`] if `degree` is 0.
    pub fn with_fine_degree(self, degree: usize) -> Result<Self, ParameterError> {
        check_degree(Parameter::FineDegree, degree)?;
        Ok(Self {
            fine_degree: degree,
            ..self
        })
    }

    /// The strength-of-connection threshold `θ` of the aggregation.
    #[must_use]
    pub fn strength(&self) -> f64 {
        self.strength
    }

    /// The threshold `θ_F` below which a particle's coupling is lumped into
    /// its diagonal block in the matrix `Â_F` that smooths the finest
    /// prolongator, `P = (I − ω D_F⁻¹ Â_F) T`.
    #[must_use]
    pub fn filter(&self) -> f64 {
        self.filter
    }

    /// The Chebyshev degree of each pre- and post-smoothing sweep on the
    /// finest level, the particles.
    #[must_use]
    pub fn fine_degree(&self) -> usize {
        self.fine_degree
    }

    /// The Chebyshev degree of each pre- and post-smoothing sweep on the
    /// coarse levels.
    #[must_use]
    pub fn coarse_degree(&self) -> usize {
        self.coarse_degree
    }

    /// The largest number of unknowns solved directly on the coarsest level.
    #[must_use]
    pub fn coarse_unknowns(&self) -> usize {
        self.coarse_unknowns
    }
}

/// A Chebyshev degree, at least 1.
fn check_degree(name: Parameter, degree: usize) -> Result<(), ParameterError> {
    if degree == 0 {
        return Err(ParameterError::new("amg", name, 0.0, "at least 1"));
    }
    Ok(())
}

impl Default for AmgSettings {
    /// `θ = 0` (aggregates of every coupled neighbour: on a cloth with
    /// bending springs, a particle's neighbours two apart), `θ_F = 0.1`
    /// (on the cloth, stretch springs only), Chebyshev degree 1 on
    /// the particles and 2 on the coarse levels, a coarsest level of at
    /// most 2 000 unknowns. Measured on cloth of 100² … 1000² particles
    /// (`benches/README.md`): against `θ = θ_F ∈ {0.02, 0.08}`, a third
    /// fewer coarse unknowns and half the coarse operators' entries for a
    /// few more iterations and faster solves; against degree 1 everywhere,
    /// iterations that grow 1.3× instead of 1.8× from 100² to 1000²;
    /// against degree 2 everywhere, on the nearly flat cloth as many
    /// iterations within four, each with three products of the fine matrix
    /// instead of five, so solves 1.1–1.6× faster (more at larger sizes).
    /// On a curved, swinging cloth degree 2 on the particles saves more
    /// iterations (35 against 53 at 100²) and is as fast at 200², 1.2×
    /// slower at 400²; on a tetrahedral lattice it halves them.
    fn default() -> Self {
        Self {
            strength: 0.0,
            filter: 0.1,
            fine_degree: 1,
            coarse_degree: 2,
            coarse_unknowns: 2000,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_name_the_parameter_out_of_range_and_set_the_finest_degree_apart() {
        let settings = AmgSettings::new(0.0, 0.1, 3, 100).unwrap();
        assert_eq!((settings.fine_degree(), settings.coarse_degree()), (3, 3));
        let settings = settings.with_fine_degree(1).unwrap();
        assert_eq!((settings.fine_degree(), settings.coarse_degree()), (1, 3));
        let defaults = AmgSettings::default();
        assert_eq!((defaults.fine_degree(), defaults.coarse_degree()), (1, 2));
        for (error, parameter) in [
            (settings.with_fine_degree(0), Parameter::FineDegree),
            (
                AmgSettings::new(0.0, 0.1, 0, 100),
                Parameter::SmootherDegree,
            ),
            (AmgSettings::new(1.0, 0.1, 2, 100), Parameter::Strength),
            (AmgSettings::new(0.0, -0.1, 2, 100), Parameter::Filter),
            (AmgSettings::new(0.0, 0.1, 2, 5), Parameter::CoarseUnknowns),
        ] {
            assert_eq!(error.unwrap_err().parameter, parameter);
        }
    }
}
