//! The model file as plain values: what the text holds, typed, with the defaults of absent keys
//! filled in, and nothing validated beyond types and shape (docs/data-and-reports.md#model-file).

use serde::{Deserialize, Deserializer, Serialize};
use serde_json::{Map, Value};

/// A report: any JSON object (the fit's report, which loaders of the model ignore).
pub type Report = Map<String, Value>;

/// The kind of axis, which says what the positions and forces are measured in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    /// Positions in m, forces in N.
    Linear,
    /// Positions in rad, forces in N·m.
    Rotary,
}

impl Units {
    /// The spelling in the file: `"linear"` or `"rotary"`.
    pub const fn key(self) -> &'static str {
        match self {
            Units::Linear => "linear",
            Units::Rotary => "rotary",
        }
    }
}

/// The friction parameters: the object of a parameter file (docs/parameters.md#keys), the
/// `friction` of a model file. Absent optional keys are `None` (or 0 for `sigma1` and `sigma2`);
/// an optional key given as `null` is refused, so that a key means one thing.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)] // the paper's names, spelled as the file spells them
pub struct Friction {
    /// Coulomb level \[N\].
    pub Fc: f64,
    /// Static level \[N\].
    pub Fs: f64,
    /// Stribeck velocity \[m/s\].
    pub Vs: f64,
    /// Stribeck shape exponent.
    pub delta: f64,
    /// Transition-curve exponent.
    pub n: f64,
    /// Micro-viscous coefficient \[N·s/m\]; 0 when absent.
    #[serde(default)]
    pub sigma1: f64,
    /// Viscous coefficient \[N·s/m\]; 0 when absent.
    #[serde(default)]
    pub sigma2: f64,
    /// Saturation forces of the Maxwell-slip elements \[N\], with `Delta`.
    #[serde(
        default,
        deserialize_with = "present",
        skip_serializing_if = "Option::is_none"
    )]
    pub W: Option<Vec<f64>>,
    /// Break deflections of the Maxwell-slip elements \[m\], with `W`.
    #[serde(
        default,
        deserialize_with = "present",
        skip_serializing_if = "Option::is_none"
    )]
    pub Delta: Option<Vec<f64>>,
    /// Stiffness of a linear hysteresis \[N/m\], instead of `W` and `Delta`.
    #[serde(
        default,
        deserialize_with = "present",
        skip_serializing_if = "Option::is_none"
    )]
    pub sigma0: Option<f64>,
    /// Coulomb level for v < 0 \[N\]; `Fc` when absent.
    #[serde(
        default,
        deserialize_with = "present",
        skip_serializing_if = "Option::is_none"
    )]
    pub Fc_neg: Option<f64>,
    /// Static level for v < 0 \[N\]; `Fs` when absent.
    #[serde(
        default,
        deserialize_with = "present",
        skip_serializing_if = "Option::is_none"
    )]
    pub Fs_neg: Option<f64>,
    /// Viscous coefficient for v < 0 \[N·s/m\]; `sigma2` when absent. Not a key of version 1
    /// model files.
    #[serde(
        default,
        deserialize_with = "present",
        skip_serializing_if = "Option::is_none"
    )]
    pub sigma2_neg: Option<f64>,
}

/// A value that must be there when its key is: `null` is refused (a missing key takes the
/// default through `#[serde(default)]`, which never calls this).
fn present<'de, D, T>(deserializer: D) -> Result<Option<T>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    T::deserialize(deserializer).map(Some)
}

/// One periodic part of a position-dependent term: the period and the harmonics' amplitudes
/// (`cos[k-1]`, `sin[k-1]` for harmonic k). All three keys are required.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Ripple {
    /// The period \[m or rad\].
    pub period: f64,
    /// Amplitudes of cos(2πk·x/period), k = 1, 2, …
    pub cos: Vec<f64>,
    /// Amplitudes of sin(2πk·x/period), k = 1, 2, …
    pub sin: Vec<f64>,
}

/// A term that depends on the position alone (docs/model.md#position-dependent-level): a trend
/// along the stroke (Legendre coefficients of p = clip((x − `middle`)/`half_stroke`, −1, 1)) and
/// ripples. As `level`, its amplitudes are relative to the friction level; as `position_force`,
/// they are forces \[N or N·m\].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PositionTerms {
    /// Middle of the stroke \[m or rad\]; 0 when absent.
    #[serde(default)]
    pub middle: f64,
    /// Half the stroke \[m or rad\]; 1 when absent.
    #[serde(default = "one")]
    pub half_stroke: f64,
    /// The trend's coefficients (t1, t2); zeros when absent.
    #[serde(default)]
    pub trend: [f64; 2],
    /// The ripples; none when absent.
    #[serde(default)]
    pub ripples: Vec<Ripple>,
}

fn one() -> f64 {
    1.0
}

impl Default for PositionTerms {
    /// Every key at its default: flat, no ripples.
    fn default() -> Self {
        PositionTerms {
            middle: 0.0,
            half_stroke: 1.0,
            trend: [0.0; 2],
            ripples: Vec::new(),
        }
    }
}

/// The measurement terms: a constant force `offset` \[N or N·m\] and an `inertia` \[kg or kg·m²\]
/// times the acceleration, which the log's force held but which are not friction.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Measurement {
    /// Force offset; 0 when absent.
    #[serde(default)]
    pub offset: f64,
    /// Inertia; 0 when absent.
    #[serde(default)]
    pub inertia: f64,
}

/// Which column of a log the model's motion signal is made from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Source {
    /// The log's `v` column.
    Velocity,
    /// The log's `x` column.
    Position,
}

/// How the model's motion signal is made from a log, as identify chose it: the `source`
/// column through a zero-phase 4th-order Butterworth low-pass at `cutoff` Hz, or as logged
/// (`cutoff` `None`). Both keys are required (`"cutoff": null` for none). The acceleration of
/// the inertia term comes from the same column through a low-pass at `acceleration_cutoff` Hz
/// (a key of version 3, optional); without it, at the lower of `cutoff` and a tenth of the
/// Nyquist frequency.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Reconstruction {
    /// The column.
    pub source: Source,
    /// The low-pass cutoff \[Hz\], or `None` for the signal as logged.
    #[serde(deserialize_with = "Option::deserialize")]
    pub cutoff: Option<f64>,
    /// The acceleration's low-pass cutoff \[Hz\], or `None` for the default (the lower of
    /// `cutoff` and a tenth of the Nyquist frequency). Not a key of version 2 model files.
    #[serde(
        default,
        deserialize_with = "present",
        skip_serializing_if = "Option::is_none"
    )]
    pub acceleration_cutoff: Option<f64>,
}

/// A model file (docs/data-and-reports.md#model-file) as plain values: the friction model and
/// what the fit found beside it. [`ModelFile::validate`] builds the model's validated objects.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelFile {
    /// The kind of axis.
    pub units: Units,
    /// The friction parameters.
    pub friction: Friction,
    /// The position-dependent level (relative amplitudes), or none.
    pub level: Option<PositionTerms>,
    /// A force that depends on the position alone (cogging, gear mesh), added in both
    /// directions, or none.
    pub position_force: Option<PositionTerms>,
    /// The measurement terms (not friction).
    pub measurement: Measurement,
    /// How the motion signal is made from a log; `None` is version 1's: the position through a
    /// zero-phase low-pass at a tenth of the Nyquist frequency, and its acceleration too.
    pub reconstruction: Option<Reconstruction>,
    /// The fit's report, or none.
    pub report: Option<Report>,
}

impl ModelFile {
    /// A model file of `friction` alone, every other key at its default (what a parameter file
    /// loads as): linear units, no level, no position force, no measurement terms, the default
    /// reconstruction, no report.
    pub fn new(friction: Friction) -> Self {
        ModelFile {
            units: Units::Linear,
            friction,
            level: None,
            position_force: None,
            measurement: Measurement::default(),
            reconstruction: None,
            report: None,
        }
    }
}
