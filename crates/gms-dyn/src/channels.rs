//! What every holder of channel states shares: the hysteresis memory of one channel seen as a
//! flat slice (to copy states in and out of caller arrays), allocation that reports running
//! out of memory, and all-or-nothing runs across channels.

use gms_core::InChannel;

use crate::error::Error;

/// The memory of one channel: N element positions for Maxwell slip, nothing for a linear spring.
pub(crate) trait Memory: Copy + Send + Sync {
    /// Number of f64 slots (N, or 0).
    const LEN: usize;
    /// The slots, [`Memory::LEN`] of them.
    fn values(&self) -> &[f64];
    /// Copies `values` ([`Memory::LEN`] of them) into the slots.
    fn write(&mut self, values: &[f64]);
}

impl<const N: usize> Memory for [f64; N] {
    const LEN: usize = N;
    fn values(&self) -> &[f64] {
        self
    }
    fn write(&mut self, values: &[f64]) {
        self.copy_from_slice(values);
    }
}

impl Memory for () {
    const LEN: usize = 0;
    fn values(&self) -> &[f64] {
        &[]
    }
    fn write(&mut self, _values: &[f64]) {}
}

/// `channels` copies of `state`; a count that does not fit in memory is an error, not an abort.
pub(crate) fn states<S: Clone>(state: S, channels: usize) -> Result<Vec<S>, Error> {
    let mut states = Vec::new();
    states
        .try_reserve_exact(channels)
        .map_err(|_| Error::OutOfMemory {
            channels,
            bytes_each: core::mem::size_of::<S>(),
        })?;
    states.resize(channels, state);
    Ok(states)
}

/// Refuses a channel index beyond `channels`.
pub(crate) fn check_channel(channel: usize, channels: usize) -> Result<(), Error> {
    if channel < channels {
        Ok(())
    } else {
        Err(Error::ChannelIndex { channel, channels })
    }
}

/// The number of samples per channel of a (channels × samples) row-major input.
pub(crate) fn samples_per_channel(len: usize, channels: usize) -> Result<usize, Error> {
    if channels > 0 && len % channels == 0 {
        Ok(len / channels)
    } else {
        Err(Error::SignalShape { len, channels })
    }
}

/// Refuses an output slice whose length differs from the input's.
pub(crate) fn check_output(expected: usize, got: usize) -> Result<(), Error> {
    if expected == got {
        Ok(())
    } else {
        Err(gms_core::Error::LengthMismatch { expected, got }.into())
    }
}

/// Runs every channel (`run` returns one result per state), all or nothing: a channel that fails
/// has already put its own state back (gms-core does), the others are put back from a copy. The
/// error names the first failing channel when there are several.
pub(crate) fn all_or_nothing<S: Clone>(
    states: &mut Vec<S>,
    run: impl FnOnce(&mut [S]) -> Option<(usize, gms_core::Error)>,
) -> Result<(), Error> {
    let several = states.len() > 1;
    if !several {
        // One channel: gms-core's own all-or-nothing is enough, no copy needed.
        return run(states).map_or(Ok(()), |(_, error)| Err(Error::Core(error)));
    }
    // The copy is fallible like the states themselves: a bank that fits once may not fit twice.
    let mut before = Vec::new();
    before
        .try_reserve_exact(states.len())
        .map_err(|_| Error::OutOfMemory {
            channels: states.len(),
            bytes_each: core::mem::size_of::<S>(),
        })?;
    before.extend_from_slice(states);
    match run(states) {
        None => Ok(()),
        Some((channel, error)) => {
            *states = before;
            Err(Error::Channel(InChannel { channel, error }))
        }
    }
}
