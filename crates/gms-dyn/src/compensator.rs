//! One axis of friction compensation, whatever its hysteresis: the object behind both the
//! Python `Compensator` and the C `leuven_rt_compensator`.
//!
//! Creating one allocates once (its size depends on the number of elements); stepping, swapping
//! parameters and resetting never allocate.

use gms_core::{Hysteresis, Level, Mode, Params, PositionForce, State};

use crate::channels::Memory;
use crate::error::Error;
use crate::kind::HysteresisKind;
use crate::params::{with_params, InParameterSet, ParameterSet, RawParams};

/// A copy of a compensator's model state.
#[derive(Clone, Debug, PartialEq)]
pub struct CompensatorState {
    /// The friction state z.
    pub z: f64,
    /// The element positions ζ (empty for linear hysteresis).
    pub zeta: Vec<f64>,
    /// The last position (observer mode, after the first sample).
    pub last_position: Option<f64>,
}

/// One axis of friction compensation at a fixed sample time.
pub struct Compensator {
    axis: Box<dyn Axis>,
}

/// gms-core's compensator for one hysteresis type, behind a trait object.
trait Axis: Send + Sync {
    fn step(&mut self, input: f64) -> Result<f64, gms_core::Error>;
    fn step_trajectory(&mut self, v: f64, x: f64) -> Result<f64, gms_core::Error>;
    fn set_position(&mut self, x: f64) -> Result<(), gms_core::Error>;
    fn position(&self) -> Option<f64>;
    fn level(&self) -> Level;
    fn set_level(&mut self, level: &Level) -> Result<(), gms_core::Error>;
    fn position_force(&self) -> PositionForce;
    fn set_position_force(&mut self, force: &PositionForce) -> Result<(), gms_core::Error>;
    fn set_params(&mut self, params: &ParameterSet) -> Result<(), Error>;
    fn reset(&mut self);
    fn output(&self) -> f64;
    fn dt(&self) -> f64;
    fn mode(&self) -> Mode;
    fn kind(&self) -> HysteresisKind;
    fn state(&self) -> CompensatorState;
}

impl<H> Axis for gms_core::Compensator<H>
where
    H: InParameterSet<Memory: Memory> + Send + Sync,
{
    #[inline]
    fn step(&mut self, input: f64) -> Result<f64, gms_core::Error> {
        gms_core::Compensator::step(self, input)
    }

    #[inline]
    fn step_trajectory(&mut self, v: f64, x: f64) -> Result<f64, gms_core::Error> {
        gms_core::Compensator::step_trajectory(self, v, x)
    }

    fn set_position(&mut self, x: f64) -> Result<(), gms_core::Error> {
        gms_core::Compensator::set_position(self, x)
    }

    fn position(&self) -> Option<f64> {
        gms_core::Compensator::position(self)
    }

    fn level(&self) -> Level {
        *gms_core::Compensator::level(self)
    }

    fn set_level(&mut self, level: &Level) -> Result<(), gms_core::Error> {
        gms_core::Compensator::set_level(self, *level)
    }

    fn position_force(&self) -> PositionForce {
        *gms_core::Compensator::position_force(self)
    }

    fn set_position_force(&mut self, force: &PositionForce) -> Result<(), gms_core::Error> {
        gms_core::Compensator::set_position_force(self, *force)
    }

    fn set_params(&mut self, params: &ParameterSet) -> Result<(), Error> {
        let Some(params) = H::find(params) else {
            return Err(Error::Incompatible {
                expected: self.kind(),
                got: params.kind(),
            });
        };
        gms_core::Compensator::set_params(self, params);
        Ok(())
    }

    fn reset(&mut self) {
        gms_core::Compensator::reset(self);
    }

    fn output(&self) -> f64 {
        gms_core::Compensator::output(self)
    }

    fn dt(&self) -> f64 {
        gms_core::Compensator::dt(self)
    }

    fn mode(&self) -> Mode {
        gms_core::Compensator::mode(self)
    }

    fn kind(&self) -> HysteresisKind {
        match <H::Memory as Memory>::LEN {
            0 => HysteresisKind::Linear,
            elements => HysteresisKind::Maxwell { elements },
        }
    }

    fn state(&self) -> CompensatorState {
        let State {
            z,
            memory,
            last_position,
        } = gms_core::Compensator::state(self);
        CompensatorState {
            z: *z,
            zeta: memory.values().to_vec(),
            last_position: *last_position,
        }
    }
}

fn boxed<H>(params: Params<H>, dt: f64, mode: Mode, terms: &Terms) -> Result<Box<dyn Axis>, Error>
where
    H: InParameterSet<Memory: Memory> + Hysteresis + Send + Sync + 'static,
{
    let mut compensator = gms_core::Compensator::new(params, dt, mode)?;
    if let Some(x) = terms.start {
        compensator = compensator.with_start_position(x)?;
    }
    Ok(Box::new(
        compensator
            .with_level(terms.level)?
            .with_position_force(terms.position_force)?,
    ))
}

/// What a compensator is built with beside its parameters: the position-dependent terms and the
/// axis's start position (required in feedforward mode when a term is given).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Terms {
    /// The start position \[m or rad\]: where feedforward mode places the terms from.
    pub start: Option<f64>,
    /// The position-dependent level ([`Level::none`] for none).
    pub level: Level,
    /// The position force ([`PositionForce::none`] for none).
    pub position_force: PositionForce,
}

impl Compensator {
    /// A compensator at rest with sample time `dt` \[s\].
    ///
    /// # Errors
    /// `dt` not finite and > 0.
    pub fn new(params: &ParameterSet, dt: f64, mode: Mode) -> Result<Self, Error> {
        Self::with_terms(params, dt, mode, &Terms::default())
    }

    /// A compensator at rest with a position-dependent level and a position force
    /// (docs/model.md#position-dependent-level): its output is
    /// factor(x)·(F − σ2(v)·v) + σ2(v)·v + r(x), placed from `terms.start` in feedforward mode.
    ///
    /// # Errors
    /// `dt` not finite and > 0, a start position that is not finite, or (feedforward mode) a
    /// level or a position force without a start position (`Missing` naming `x`).
    pub fn with_terms(
        params: &ParameterSet,
        dt: f64,
        mode: Mode,
        terms: &Terms,
    ) -> Result<Self, Error> {
        Ok(Self {
            axis: with_params!(*params, params => boxed(params, dt, mode, terms)?),
        })
    }

    /// Sets the position of the axis, from which feedforward mode places the terms (observer
    /// mode takes the position from its input).
    ///
    /// # Errors
    /// A non-finite `x`; nothing changes.
    pub fn set_position(&mut self, x: f64) -> Result<(), gms_core::Error> {
        self.axis.set_position(x)
    }

    /// The feedforward position: the start position, then the desired positions stepped or the
    /// desired velocities integrated since; `None` until a start position is given.
    pub fn position(&self) -> Option<f64> {
        self.axis.position()
    }

    /// Replaces the position-dependent level between two samples; the model state carries over.
    ///
    /// # Errors
    /// `Missing` naming `x`: feedforward mode without a start position; nothing changes.
    pub fn set_level(&mut self, level: &Level) -> Result<(), gms_core::Error> {
        self.axis.set_level(level)
    }

    /// The position-dependent level ([`Level::none`] when none was given).
    pub fn level(&self) -> Level {
        self.axis.level()
    }

    /// Replaces the position force between two samples, as [`Compensator::set_level`].
    ///
    /// # Errors
    /// `Missing` naming `x`: feedforward mode without a start position; nothing changes.
    pub fn set_position_force(&mut self, force: &PositionForce) -> Result<(), gms_core::Error> {
        self.axis.set_position_force(force)
    }

    /// The position force ([`PositionForce::none`] when none was given).
    pub fn position_force(&self) -> PositionForce {
        self.axis.position_force()
    }

    /// The friction force for one sample of a planned trajectory: the desired velocity `v`
    /// drives the model, the desired position `x` places the terms (gms-core's
    /// `Compensator::step_trajectory`).
    ///
    /// # Errors
    /// A non-finite `v` or `x`, or a non-finite force; the state and output are unchanged.
    #[inline]
    pub fn step_trajectory(&mut self, v: f64, x: f64) -> Result<f64, gms_core::Error> {
        self.axis.step_trajectory(v, x)
    }

    /// The friction force to add to the command for this sample; `input` is the desired
    /// velocity (feedforward) or the measured position (observer).
    ///
    /// # Errors
    /// A non-finite input, a position jump whose velocity is not finite, or a non-finite
    /// force; the state and [`Compensator::output`] are unchanged.
    #[inline]
    pub fn step(&mut self, input: f64) -> Result<f64, gms_core::Error> {
        self.axis.step(input)
    }

    /// Swaps in validated parameters of the same kind and number of elements; the hysteresis
    /// force carries over, so the output has no jump.
    ///
    /// # Errors
    /// [`Error::Incompatible`]; nothing changes.
    pub fn set_params(&mut self, params: &ParameterSet) -> Result<(), Error> {
        self.axis.set_params(params)
    }

    /// Validates `raw` and swaps it in, as [`Compensator::set_params`]. The kind and number of
    /// elements are compared first, so that a set of the wrong size is called that, whatever
    /// else is wrong with it. Never allocates.
    ///
    /// # Errors
    /// [`Error::Incompatible`], or the first rule `raw` breaks; nothing changes.
    pub fn set_raw_params(&mut self, raw: &RawParams<'_>) -> Result<(), Error> {
        let expected = self.axis.kind();
        if raw.kind() != expected {
            return Err(Error::Incompatible {
                expected,
                got: raw.kind(),
            });
        }
        self.axis.set_params(&raw.validate()?)
    }

    /// Back to rest: relaxed state, no previous position, output 0.
    pub fn reset(&mut self) {
        self.axis.reset();
    }

    /// The last force returned by [`Compensator::step`] (0 before the first).
    pub fn output(&self) -> f64 {
        self.axis.output()
    }

    /// The sample time \[s\].
    pub fn dt(&self) -> f64 {
        self.axis.dt()
    }

    /// Feedforward or observer.
    pub fn mode(&self) -> Mode {
        self.axis.mode()
    }

    /// The kind of hysteresis and its number of elements.
    pub fn kind(&self) -> HysteresisKind {
        self.axis.kind()
    }

    /// A copy of the model state.
    pub fn state(&self) -> CompensatorState {
        self.axis.state()
    }
}
