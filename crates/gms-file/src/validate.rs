//! From plain values to the validated objects of gms-dyn and gms-core, each value checked by the
//! layer that owns its rule, and each refusal given the key path of the value.

use gms_core::{Error as Core, Field};
use gms_dyn::{
    Level, ParameterSet, PositionForce, RawElements, RawParams, RippleTerms, MAX_HARMONICS,
};

use crate::error::{FileError, Problem};
use crate::file::{Friction, ModelFile, PositionTerms};

/// The validated objects of a model file: what a compensator or a simulation takes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Model {
    /// The friction parameters, validated by gms-dyn (gms-core's rules).
    pub params: ParameterSet,
    /// The position-dependent level, validated by gms-core; the flat level when the file has
    /// none.
    pub level: Level,
    /// The position force, validated by gms-core; none when the file has none.
    pub position_force: PositionForce,
}

impl Friction {
    /// The parameters as gms-dyn takes them (the direction-dependent levels resolved), not yet
    /// validated. `W` without `Delta` (or the reverse) is refused here, naming the missing key.
    pub fn raw(&self) -> Result<RawParams<'_>, FileError> {
        let elements = match (&self.W, &self.Delta) {
            (Some(w), Some(delta)) => Some(RawElements { w, delta }),
            (None, None) => None,
            (Some(_), None) | (None, Some(_)) => {
                let (given, missing) = if self.W.is_some() {
                    ("W", "Delta")
                } else {
                    ("Delta", "W")
                };
                return Err(FileError::Shape {
                    key: missing.to_owned(),
                    problem: Problem::MissingKey,
                    message: format!(
                        "missing key: `{given}` is given, and Maxwell slip needs both `W` and \
                         `Delta`"
                    ),
                });
            }
        };
        Ok(RawParams {
            fc: self.Fc,
            fs: self.Fs,
            vs: self.Vs,
            delta: self.delta,
            n: self.n,
            sigma1: self.sigma1,
            sigma2: self.sigma2,
            fc_neg: self.Fc_neg.unwrap_or(self.Fc),
            fs_neg: self.Fs_neg.unwrap_or(self.Fs),
            sigma2_neg: self.sigma2_neg,
            sigma0: self.sigma0,
            elements,
        })
    }

    /// Checks every rule of docs/parameters.md#rules (gms-dyn's [`RawParams::validate`]) and
    /// returns the validated set; a refusal names the key as a parameter file has it (`W[2]`;
    /// [`ModelFile::validate`] names it under `friction`).
    pub fn validate(&self) -> Result<ParameterSet, FileError> {
        self.raw()?.validate().map_err(|error| FileError::Rule {
            key: friction_key(&error),
            error,
        })
    }
}

impl PositionTerms {
    /// The harmonics of every ripple: a ripple in a file has at least one (an empty one would
    /// hold a period that nothing uses). `prefix` is the key of the object (`level`).
    fn check_harmonics(&self, prefix: &str) -> Result<(), FileError> {
        for (index, ripple) in self.ripples.iter().enumerate() {
            if ripple.cos.is_empty() && ripple.sin.is_empty() {
                return Err(FileError::Invalid {
                    key: format!("{prefix}.ripples[{index}]"),
                    rule: "harmonic_lengths",
                    message: format!(
                        "a ripple needs 1 to {MAX_HARMONICS} harmonics in `cos` and `sin`, got \
                         none"
                    ),
                });
            }
        }
        Ok(())
    }

    /// The ripples as gms-core takes them.
    fn terms(&self) -> Vec<RippleTerms<'_>> {
        self.ripples
            .iter()
            .map(|ripple| RippleTerms {
                period: ripple.period,
                cos: &ripple.cos,
                sin: &ripple.sin,
            })
            .collect()
    }

    /// The level of these terms, validated by gms-core's [`Level::new`]; a refusal names the
    /// key under `level`.
    pub fn level(&self) -> Result<Level, FileError> {
        self.check_harmonics("level")?;
        Level::new(self.middle, self.half_stroke, self.trend, &self.terms()).map_err(|error| {
            FileError::Rule {
                key: terms_key("level", &error),
                error: error.into(),
            }
        })
    }

    /// The position force of these terms, validated by gms-core's [`PositionForce::new`]; a
    /// refusal names the key under `position_force`.
    pub fn position_force(&self) -> Result<PositionForce, FileError> {
        self.check_harmonics("position_force")?;
        PositionForce::new(self.middle, self.half_stroke, self.trend, &self.terms()).map_err(
            |error| FileError::Rule {
                key: terms_key("position_force", &error),
                error: error.into(),
            },
        )
    }
}

impl ModelFile {
    /// Checks every value and builds the validated objects: the friction by gms-dyn's
    /// [`RawParams::validate`], the level by gms-core's [`Level::new`], and the rules of the file
    /// itself (finite measurement terms, a finite cutoff > 0, at least one harmonic per ripple).
    /// The position force is validated by gms-core's [`PositionForce::new`].
    /// The first refusal names the key.
    pub fn validate(&self) -> Result<Model, FileError> {
        let params = self
            .friction
            .validate()
            .map_err(|error| error.under("friction"))?;
        let level = match &self.level {
            Some(terms) => terms.level()?,
            None => Level::none(),
        };
        let position_force = match &self.position_force {
            Some(terms) => terms.position_force()?,
            None => PositionForce::none(),
        };
        for (key, value) in [
            ("measurement.offset", self.measurement.offset),
            ("measurement.inertia", self.measurement.inertia),
        ] {
            if !value.is_finite() {
                return Err(FileError::Invalid {
                    key: key.to_owned(),
                    rule: "not_finite_value",
                    message: format!("must be finite, got {}", gms_core::Shown(value)),
                });
            }
        }
        if let Some(reconstruction) = self.reconstruction {
            for (key, cutoff, otherwise) in [
                (
                    "reconstruction.cutoff",
                    reconstruction.cutoff,
                    "null for the signal as logged",
                ),
                (
                    "reconstruction.acceleration_cutoff",
                    reconstruction.acceleration_cutoff,
                    "absent for the default",
                ),
            ] {
                if let Some(cutoff) = cutoff.filter(|c| !(c.is_finite() && *c > 0.0)) {
                    return Err(FileError::Invalid {
                        key: key.to_owned(),
                        rule: "not_positive",
                        message: format!(
                            "must be finite and > 0 [Hz] (or {otherwise}), got {}",
                            gms_core::Shown(cutoff)
                        ),
                    });
                }
            }
        }
        Ok(Model {
            params,
            level,
            position_force,
        })
    }
}

/// The key path of a refused friction parameter, in a parameter file.
fn friction_key(error: &gms_dyn::Error) -> String {
    use gms_dyn::Error as Dyn;
    match error {
        Dyn::Core(Core::Element { field, index, .. }) => format!("{field}[{index}]"),
        Dyn::Core(
            Core::NotPositive { field, .. }
            | Core::Negative { field, .. }
            | Core::NotFiniteValue { field, .. }
            | Core::StaticBelowCoulomb { field, .. }
            | Core::NotFinite { field, .. },
        ) => field.key().to_owned(),
        Dyn::Core(Core::ForceSumOverflow { .. } | Core::ElementsTooWeak { .. })
        | Dyn::EmptyElements
        | Dyn::TooManyElements { .. } => "W".to_owned(),
        Dyn::Core(Core::StiffnessOverflow { index, .. } | Core::DeltaTooNarrow { index, .. }) => {
            format!("Delta[{index}]")
        }
        Dyn::Core(Core::StiffnessSumOverflow) | Dyn::ElementLengths { .. } => "Delta".to_owned(),
        Dyn::BothHysteresis | Dyn::NeitherHysteresis => "sigma0".to_owned(),
        // No other refusal comes from RawParams::validate; one added later is named by its
        // message alone.
        _ => String::new(),
    }
}

/// The key path, under `prefix` (`level` or `position_force`), of a refused position term.
fn terms_key(prefix: &str, error: &Core) -> String {
    let key = match *error {
        Core::NotFiniteValue { field, .. } | Core::NotPositive { field, .. } => {
            field.key().to_owned()
        }
        Core::NotFinite {
            field: Field::trend,
            index,
            ..
        } => format!("trend[{index}]"),
        Core::TooManyRipples { .. } => "ripples".to_owned(),
        Core::RipplePeriod { ripple, .. }
        | Core::PhaseUnresolved {
            field: Field::period,
            index: ripple,
            ..
        } => format!("ripples[{ripple}].period"),
        Core::PhaseUnresolved { field, .. } => field.key().to_owned(),
        Core::HarmonicLengths { ripple, .. } | Core::TooManyHarmonics { ripple, .. } => {
            format!("ripples[{ripple}]")
        }
        Core::RippleCoefficient {
            field,
            ripple,
            index,
            ..
        } => format!("ripples[{ripple}].{field}[{index}]"),
        _ => return prefix.to_owned(),
    };
    format!("{prefix}.{key}")
}
