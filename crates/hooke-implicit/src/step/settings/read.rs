//! [`ImplicitSettings::from_keys`]: settings from keys and values, checked
//! as the keys module's rules say.

use hooke_core::{Named, Parameter};

use super::ImplicitSettings;
use super::keys::{Key, KeyError, KeyValue};
use crate::linear::cg::PcgSettings;
use crate::linear::cholesky::{Supernodes, WeakSprings};
use crate::linear::solver::{AmgRenewal, LinearSolver};
use crate::minimize::minimizer::Minimizer;
use crate::step::error_control::ErrorControl;
use crate::step::scheme::Scheme;

impl ImplicitSettings {
    /// The settings the keys `keys` give, each key its value, every other
    /// setting at its default ([`ImplicitSettings::default`]): the reader
    /// of scene files' `[integrator]` tables, of reports and of keyword
    /// arguments. The keys are those [`ImplicitSettings::keys`] writes:
    /// `scheme` (`"backward-euler"` or `"bdf2"`), `solver`, PCG's
    /// `tolerance` and `max_iterations`, `step` (the minimiser; `"converged"`
    /// is `"newton"`'s old name), L-BFGS's `history` and `carried_pairs`
    /// (by default [`Minimizer::CARRIED`], at most `history`),
    /// `newton_iterations`, `newton_tolerance`, `inexact_newton`,
    /// `amg_renewal`, `weak_springs`, `supernodes`, `max_halvings`,
    /// `strict`, `compressed_springs`, and `rtol` and `atol`, either of
    /// which turns error control on (the other at [`ErrorControl::RELATIVE`]
    /// or [`ErrorControl::ABSOLUTE`]). A key given twice takes its last
    /// value.
    ///
    /// ```
    /// use hooke_implicit::{ImplicitSettings, KeyValue, LinearSolver, PcgSettings};
    /// let settings = ImplicitSettings::from_keys([
    ///     ("solver", KeyValue::Name("pcg")),
    ///     ("tolerance", KeyValue::Number(1e-8)),
    ///     ("strict", KeyValue::Switch(true)),
    /// ])?;
    /// assert_eq!(settings.solver, LinearSolver::Pcg(PcgSettings::new(1e-8, 1000)?));
    /// assert!(settings.strict);
    /// let error = ImplicitSettings::from_keys([("history", KeyValue::Count(3))]).unwrap_err();
    /// assert_eq!(
    ///     error.to_string(),
    ///     "history: got `history` with step = \"newton\", \
    ///      expected `history` only with step = \"quasi-newton\""
    /// );
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`KeyError`] naming the key: an unknown key or name, a value of the
    /// wrong kind, a key that does not apply to the solver or step the keys
    /// choose (PCG's keys without a PCG iteration, `history` without the
    /// quasi-Newton step …), `carried_pairs` above `history`, or a value
    /// out of range ([`ImplicitSettings::validate`], [`PcgSettings::new`],
    /// [`ErrorControl::new`]).
    pub fn from_keys<'a>(
        keys: impl IntoIterator<Item = (&'a str, KeyValue<'a>)>,
    ) -> Result<Self, KeyError> {
        let mut given = Vec::new();
        for (name, value) in keys {
            let key = Key::from_name(name).ok_or_else(|| {
                KeyError::invalid(
                    name,
                    format!("`{name}`"),
                    format!("one of {}", Key::quoted_names()),
                )
            })?;
            given.push((key, value));
        }
        let given = Given(given);
        let defaults = Self::default();
        let mut settings = Self {
            scheme: given
                .named::<Scheme>(Key::Scheme)?
                .unwrap_or(defaults.scheme),
            solver: given
                .named::<LinearSolver>(Key::Solver)?
                .unwrap_or(defaults.solver),
            minimizer: given.step()?.unwrap_or(defaults.minimizer),
            ..defaults
        };
        for &(key, _) in &given.0 {
            key.in_scope(&settings)?;
        }
        if let Minimizer::QuasiNewton { history, carried } = &mut settings.minimizer {
            if let Some(h) = given.count(Key::History)? {
                *history = h;
                *carried = Minimizer::CARRIED.min(h);
            }
            if let Some(c) = given.count(Key::CarriedPairs)? {
                if c > *history {
                    return Err(KeyError::invalid(
                        Key::CarriedPairs.name(),
                        format!("{c} with history = {history}"),
                        "at most `history`".to_owned(),
                    ));
                }
                *carried = c;
            }
        }
        if let Some(pcg) = settings.solver.pcg() {
            let tolerance = given.number(Key::Tolerance)?.unwrap_or(pcg.tolerance());
            let cap = given.count(Key::MaxIterations)?;
            let pcg = PcgSettings::new(tolerance, cap.unwrap_or(pcg.max_iterations()))
                .map_err(|e| KeyError::out_of_range(Key::of(e.parameter), e))?;
            settings.solver = settings.solver.with_pcg(pcg);
        }
        let s = &mut settings;
        s.newton_iterations = given
            .count(Key::NewtonIterations)?
            .unwrap_or(s.newton_iterations);
        s.newton_tolerance = given
            .number(Key::NewtonTolerance)?
            .unwrap_or(s.newton_tolerance);
        s.inexact_newton = given
            .switch(Key::InexactNewton)?
            .unwrap_or(s.inexact_newton);
        s.amg_renewal = given
            .named::<AmgRenewal>(Key::AmgRenewal)?
            .unwrap_or(s.amg_renewal);
        s.weak_springs = given
            .named::<WeakSprings>(Key::WeakSprings)?
            .or(s.weak_springs);
        s.supernodes = given
            .named::<Supernodes>(Key::Supernodes)?
            .unwrap_or(s.supernodes);
        if let Some(halvings) = given.count(Key::MaxHalvings)? {
            s.max_halvings = u32::try_from(halvings).map_err(|_| {
                KeyError::invalid(
                    Key::MaxHalvings.name(),
                    halvings,
                    format!("at most {}", u32::MAX),
                )
            })?;
        }
        s.strict = given.switch(Key::Strict)?.unwrap_or(s.strict);
        s.compressed = given.named(Key::CompressedSprings)?.unwrap_or(s.compressed);
        s.contact_limit = given.named(Key::ContactLimit)?.unwrap_or(s.contact_limit);
        let (rtol, atol) = (given.number(Key::Rtol)?, given.number(Key::Atol)?);
        if rtol.is_some() || atol.is_some() {
            let control = ErrorControl::new(
                rtol.unwrap_or(ErrorControl::RELATIVE),
                atol.unwrap_or(ErrorControl::ABSOLUTE),
            );
            s.error_control =
                Some(control.map_err(|e| KeyError::out_of_range(Key::of(e.parameter), e))?);
        }
        settings
            .validate()
            .map_err(|e| KeyError::out_of_range(Key::of(e.parameter), e))?;
        Ok(settings)
    }
}

impl Key {
    /// The key whose value a range error of `parameter` is about.
    fn of(parameter: Parameter) -> Self {
        match parameter {
            Parameter::Tolerance => Self::Tolerance,
            Parameter::MaxIterations => Self::MaxIterations,
            Parameter::NewtonIterations => Self::NewtonIterations,
            Parameter::RelativeTolerance => Self::Rtol,
            Parameter::AbsoluteTolerance => Self::Atol,
            _ => Self::NewtonTolerance,
        }
    }
}

/// The keys given, each with its value, in the order given.
struct Given<'a>(Vec<(Key, KeyValue<'a>)>);

impl Given<'_> {
    fn get(&self, key: Key) -> Option<KeyValue<'_>> {
        self.0
            .iter()
            .rev()
            .find(|(k, _)| *k == key)
            .map(|&(_, v)| v)
    }

    fn wrong(key: Key, value: KeyValue<'_>, expected: &str) -> KeyError {
        KeyError::invalid(key.name(), value, expected.to_owned())
    }

    /// The value of `T`'s table that `key` names.
    fn named<T: Named>(&self, key: Key) -> Result<Option<T>, KeyError> {
        self.get(key)
            .map(|value| {
                match value {
                    KeyValue::Name(name) => T::from_name(name),
                    _ => None,
                }
                .ok_or_else(|| KeyError::invalid(key.name(), value, T::quoted_names()))
            })
            .transpose()
    }

    fn count(&self, key: Key) -> Result<Option<usize>, KeyError> {
        self.get(key)
            .map(|value| {
                match value {
                    KeyValue::Count(n) => usize::try_from(n).ok(),
                    _ => None,
                }
                .ok_or_else(|| Self::wrong(key, value, "a whole number ≥ 0"))
            })
            .transpose()
    }

    fn number(&self, key: Key) -> Result<Option<f64>, KeyError> {
        self.get(key)
            .map(|value| match value {
                KeyValue::Number(x) => Ok(x),
                // A whole number is a number (as in TOML and JSON).
                KeyValue::Count(n) => Ok(n as f64),
                _ => Err(Self::wrong(key, value, "a number")),
            })
            .transpose()
    }

    fn switch(&self, key: Key) -> Result<Option<bool>, KeyError> {
        self.get(key)
            .map(|value| match value {
                KeyValue::Switch(b) => Ok(b),
                _ => Err(Self::wrong(key, value, "true or false")),
            })
            .transpose()
    }

    /// The minimiser `step` names; `"converged"` is Newton's old name.
    fn step(&self) -> Result<Option<Minimizer>, KeyError> {
        match self.get(Key::Step) {
            Some(KeyValue::Name("converged")) => Ok(Some(Minimizer::Newton)),
            Some(value) => self.named::<Minimizer>(Key::Step).map_err(|_| {
                KeyError::invalid(
                    Key::Step.name(),
                    value,
                    format!(
                        "{} (or \"converged\" for \"{}\")",
                        Minimizer::quoted_names(),
                        Minimizer::Newton.name()
                    ),
                )
            }),
            None => Ok(None),
        }
    }
}
