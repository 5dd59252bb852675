//! `_core.MassEngine`: channels of a force-driven mass on the friction model (gms-core's
//! `MassSystem`), stepped from Python. `leuven_rt.MassSystem` subclasses it.

use gms_core::Trajectory;
use gms_dyn::{MassBank, MassStates, Mechanics};
use numpy::{
    PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use crate::convert::{
    channel_count, parse_scheme, real, real_of, same_channels, scheme_name, single_channel, zeros,
};
use crate::errors::{lend, lend_mut, raise, Class, Kind, Refusal};
use crate::params::parameter_set;

/// x, v, anchor, z of every channel (B,) and zeta (B, N).
type StateArrays<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray2<f64>>,
);

/// Channels of a mass on the friction model, with an optional (dragged) spring.
#[pyclass(subclass, module = "leuven_rt._core")]
pub struct MassEngine {
    bank: MassBank,
    params: Py<PyAny>,
}

#[pymethods]
impl MassEngine {
    #[new]
    #[pyo3(signature = (params, mass, stiffness = None, drive_speed = None, channels = 1, scheme = None))]
    fn new(
        params: &Bound<'_, PyAny>,
        mass: &Bound<'_, PyAny>,
        stiffness: Option<&Bound<'_, PyAny>>,
        drive_speed: Option<&Bound<'_, PyAny>>,
        channels: i64,
        scheme: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let number = |value: &Bound<'_, PyAny>, name: &str| real_of(value, name, Class::Parameter);
        let mechanics = Mechanics {
            mass: number(mass, "mass")?,
            stiffness: stiffness.map_or(Ok(0.0), |value| number(value, "stiffness"))?,
            drive_speed: drive_speed.map_or(Ok(0.0), |value| number(value, "drive_speed"))?,
        };
        let channels = channel_count(channels)?;
        let scheme = parse_scheme(scheme)?;
        let set = parameter_set(params)?;
        Ok(Self {
            bank: MassBank::new(&set, mechanics, channels, scheme).map_err(raise)?,
            params: params.clone().unbind(),
        })
    }

    /// The friction parameters.
    #[getter]
    fn params(slf: &Bound<'_, Self>) -> PyResult<Py<PyAny>> {
        Ok(lend(slf)?.params.clone_ref(slf.py()))
    }
    /// Mass m [kg].
    #[getter]
    fn mass(slf: &Bound<'_, Self>) -> PyResult<f64> {
        Ok(lend(slf)?.bank.mechanics().mass)
    }
    /// Spring stiffness k [N/m] (0: no spring).
    #[getter]
    fn stiffness(slf: &Bound<'_, Self>) -> PyResult<f64> {
        Ok(lend(slf)?.bank.mechanics().stiffness)
    }
    /// Speed of the spring's far end [m/s] (0: spring to ground).
    #[getter]
    fn drive_speed(slf: &Bound<'_, Self>) -> PyResult<f64> {
        Ok(lend(slf)?.bank.mechanics().drive_speed)
    }
    /// Number of channels B.
    #[getter]
    fn channels(slf: &Bound<'_, Self>) -> PyResult<usize> {
        Ok(lend(slf)?.bank.channels())
    }
    /// Number of Maxwell-slip elements N (0 for linear hysteresis).
    #[getter]
    fn elements(slf: &Bound<'_, Self>) -> PyResult<usize> {
        Ok(lend(slf)?.bank.elements())
    }
    /// 'implicit' or 'explicit'.
    #[getter]
    fn scheme(slf: &Bound<'_, Self>) -> PyResult<&'static str> {
        Ok(scheme_name(lend(slf)?.bank.scheme()))
    }

    /// One step of a single-channel system with applied force `u` held over `dt`; returns
    /// (friction force, position, velocity) at the end of the step.
    fn step(
        slf: &Bound<'_, Self>,
        u: &Bound<'_, PyAny>,
        dt: &Bound<'_, PyAny>,
    ) -> PyResult<(f64, f64, f64)> {
        let mut this = lend_mut(slf)?;
        single_channel(this.bank.channels(), "step", "system")?;
        let (u, dt) = (real(u, "u")?, real(dt, "dt")?);
        let sample = this.bank.step(0, u, dt).map_err(raise)?;
        Ok((sample.friction, sample.x, sample.v))
    }

    /// Every channel over its row of `u` (B, T), checked finite by the caller, with the GIL
    /// released; returns (3, B, T): friction force, position, velocity.
    fn _run<'py>(
        slf: &Bound<'py, Self>,
        u: PyReadonlyArray2<'py, f64>,
        dt: f64,
    ) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let py = slf.py();
        let mut this = lend_mut(slf)?;
        let shape = [u.shape()[0], u.shape()[1]];
        same_channels(shape[0], this.bank.channels(), "`u`", "system")?;
        let u = u.as_slice()?;
        let size = u.len();
        let mut out = zeros(3 * size, "u")?;
        let bank = &mut this.bank;
        py.detach(|| {
            let (friction, rest) = out.split_at_mut(size);
            let (x, v) = rest.split_at_mut(size);
            bank.run(u, dt, Trajectory { friction, x, v })
        })
        .map_err(raise)?;
        PyArray1::from_vec(py, out).reshape([3, shape[0], shape[1]])
    }

    /// Puts every channel at rest state: positions `x` and velocities `v` (B,), the spring's
    /// far end at 0, relaxed friction. Arrays are checked finite by the caller.
    fn _place(
        slf: &Bound<'_, Self>,
        x: PyReadonlyArray1<'_, f64>,
        v: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<()> {
        let mut this = lend_mut(slf)?;
        let (x, v) = (x.as_slice()?, v.as_slice()?);
        let b = this.bank.channels();
        if x.len() != b || v.len() != b {
            return Err(Refusal::new(
                Class::Input,
                Kind::Shape,
                format!("`position` and `velocity` must have shape ({b},)"),
            )
            .field(if x.len() == b { "velocity" } else { "position" })
            .into());
        }
        this.bank.place(x, v);
        Ok(())
    }

    /// Copies of (x, v, anchor, z, zeta), shapes (B,) × 4 and (B, N).
    fn _get_state<'py>(slf: &Bound<'py, Self>) -> PyResult<StateArrays<'py>> {
        let py = slf.py();
        let this = lend(slf)?;
        let (b, n) = (this.bank.channels(), this.bank.elements());
        let (mut x, mut v, mut anchor, mut z) =
            (vec![0.0; b], vec![0.0; b], vec![0.0; b], vec![0.0; b]);
        let mut zeta = vec![0.0; b * n];
        this.bank.read_state(MassStates {
            x: &mut x,
            v: &mut v,
            anchor: &mut anchor,
            z: &mut z,
            zeta: &mut zeta,
        });
        Ok((
            PyArray1::from_vec(py, x),
            PyArray1::from_vec(py, v),
            PyArray1::from_vec(py, anchor),
            PyArray1::from_vec(py, z),
            PyArray1::from_vec(py, zeta).reshape([b, n])?,
        ))
    }

    /// Restores states checked by the Python side (shapes and finiteness).
    fn _set_state(
        slf: &Bound<'_, Self>,
        x: PyReadonlyArray1<'_, f64>,
        v: PyReadonlyArray1<'_, f64>,
        anchor: PyReadonlyArray1<'_, f64>,
        z: PyReadonlyArray1<'_, f64>,
        zeta: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<()> {
        let mut this = lend_mut(slf)?;
        let (b, n) = (this.bank.channels(), this.bank.elements());
        let (x, v, anchor, z, zeta) = (
            x.as_slice()?,
            v.as_slice()?,
            anchor.as_slice()?,
            z.as_slice()?,
            zeta.as_slice()?,
        );
        if [x.len(), v.len(), anchor.len(), z.len()] != [b; 4] || zeta.len() != b * n {
            return Err(Refusal::new(
                Class::Input,
                Kind::Shape,
                format!("state must have shapes x, v, anchor, z ({b},) and zeta ({b}, {n})"),
            )
            .field("state")
            .into());
        }
        this.bank.write_state(x, v, anchor, z, zeta).map_err(raise)
    }
}
