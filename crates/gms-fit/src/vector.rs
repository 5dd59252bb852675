//! A derivative by every column at once: the shared columns and the hysteresis's own.

use crate::columns::SHARED_COLUMNS;

/// d(·)/dθ for the P = 10 + M columns: the shared ones (Fc … `sigma2_neg`) and the M of the
/// hysteresis (N weights, or σ0). Two fixed-size arrays rather than one of 10 + M, so that
/// both lengths are known to the compiler, which unrolls and vectorises the loops over them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Vector<const M: usize> {
    pub shared: [f64; SHARED_COLUMNS],
    pub own: [f64; M],
}

impl<const M: usize> Vector<M> {
    pub const ZERO: Self = Self {
        shared: [0.0; SHARED_COLUMNS],
        own: [0.0; M],
    };

    /// self += a·x.
    #[inline]
    pub fn add_scaled(&mut self, a: f64, x: &Self) {
        for (value, &term) in self.shared.iter_mut().zip(&x.shared) {
            *value += a * term;
        }
        for (value, &term) in self.own.iter_mut().zip(&x.own) {
            *value += a * term;
        }
    }

    /// self *= a.
    #[inline]
    pub fn scale(&mut self, a: f64) {
        // Two loops, not a chained iterator: a chain tests which half it is in at every value.
        for value in &mut self.shared {
            *value *= a;
        }
        for value in &mut self.own {
            *value *= a;
        }
    }

    /// Copies the P values into `row`, in column order.
    #[inline]
    pub fn write(&self, row: &mut [f64]) {
        let (shared, own) = row.split_at_mut(SHARED_COLUMNS);
        shared.copy_from_slice(&self.shared);
        own.copy_from_slice(&self.own);
    }
}

/// Σᵢ weights[i]·rows[i], summed in the order of i for every column (as repeated
/// [`Vector::add_scaled`] would), but a block of columns at a time: each block's partial sums
/// stay in registers while the rows stream past, instead of the whole sum going to memory and
/// back once per row.
#[inline]
pub(crate) fn weighted_sum<const M: usize>(weights: &[f64], rows: &[Vector<M>]) -> Vector<M> {
    let mut out = Vector::ZERO;
    out.shared = block_sum(weights, rows, |row| row.shared);
    let mut start = 0;
    while start + BLOCK <= M {
        sum_into::<M, BLOCK>(weights, rows, start, &mut out.own);
        start += BLOCK;
    }
    // The last M mod BLOCK columns, in blocks of 4, 2 and 1.
    if M - start >= 4 {
        sum_into::<M, 4>(weights, rows, start, &mut out.own);
        start += 4;
    }
    if M - start >= 2 {
        sum_into::<M, 2>(weights, rows, start, &mut out.own);
        start += 2;
    }
    if M - start >= 1 {
        sum_into::<M, 1>(weights, rows, start, &mut out.own);
    }
    out
}

/// Columns of the hysteresis summed per block: 8 partial sums are four SSE2 registers.
const BLOCK: usize = 8;

/// The block of B own columns from `start`, summed into `out`.
#[inline]
fn sum_into<const M: usize, const B: usize>(
    weights: &[f64],
    rows: &[Vector<M>],
    start: usize,
    out: &mut [f64; M],
) {
    let block = |row: &Vector<M>| -> [f64; B] {
        core::array::from_fn(|j| row.own.get(start + j).copied().unwrap_or(0.0))
    };
    let sums = block_sum(weights, rows, block);
    if let Some(slots) = out.get_mut(start..start + B) {
        slots.copy_from_slice(&sums);
    }
}

/// Σᵢ weights[i]·block(rows[i]) for one block of B columns, its B sums in registers.
#[inline]
fn block_sum<const M: usize, const B: usize>(
    weights: &[f64],
    rows: &[Vector<M>],
    block: impl Fn(&Vector<M>) -> [f64; B],
) -> [f64; B] {
    let mut sums = [0.0; B];
    for (&weight, row) in weights.iter().zip(rows) {
        for (sum, value) in sums.iter_mut().zip(block(row)) {
            *sum += weight * value;
        }
    }
    sums
}
