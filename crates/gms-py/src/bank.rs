//! What the multi-channel engines (`_core.Engine`, `_core.MassEngine`) share: per-channel
//! hysteresis memory seen as a flat slice, for copying states in and out of numpy arrays, and
//! all-or-nothing runs across channels.

use gms_core::Error;

/// The memory of one channel: N element positions for Maxwell slip, nothing for a linear spring.
pub trait Memory: Copy + Send + Sync {
    /// Number of f64 slots (N, or 0).
    const LEN: usize;
    /// The slots as a slice of length [`Memory::LEN`].
    fn values(&self) -> &[f64];
    /// Copies the slots into `out` (length [`Memory::LEN`]).
    fn read(&self, out: &mut [f64]) {
        out.copy_from_slice(self.values());
    }
    /// Copies `values` (length [`Memory::LEN`]) into the slots.
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

/// The first failing channel of per-channel results, with its error.
pub fn first_failure(
    results: impl IntoIterator<Item = Result<(), Error>>,
) -> Result<(), (usize, Error)> {
    results
        .into_iter()
        .enumerate()
        .try_for_each(|(channel, result)| result.map_err(|error| (channel, error)))
}

/// Runs every channel (`run` returns one result per state); all or nothing across channels: a
/// channel that fails has already put its own state back (gms-core does), the others are put
/// back from a copy. The error names the first failing channel.
pub fn all_or_nothing<S: Clone>(
    states: &mut Vec<S>,
    run: impl FnOnce(&mut [S]) -> Vec<Result<(), Error>>,
) -> Result<(), (usize, Error)> {
    let before = states.clone();
    let outcome = first_failure(run(states));
    if outcome.is_err() {
        *states = before;
    }
    outcome
}
