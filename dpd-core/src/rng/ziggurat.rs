//! The acceptance step of `rand_distr`'s standard-normal ziggurat, inlinable.
//!
//! `StandardNormal::sample` is a call of about 47 instructions per normal (cachegrind), most of
//! them the rare branches; about 98.5 % of draws end in its first test. [`Ziggurat::fast`] is
//! that test alone: with the layer `i` (low 8 bits of the draw) and `u` in `[-1, 1)` (its top
//! 52 bits) it returns `u x_i` when `|u x_i| < x_{i+1}`, and `None` otherwise, when the caller
//! hands the same draw to `StandardNormal` itself. The result is therefore bitwise that of
//! `rand_distr` whatever happens.
//!
//! `rand_distr` keeps its layer table private, so it is read from `StandardNormal` once, by
//! sampling from a generator whose first draw is `u = -1/2` in layer `i` and whose second is
//! the largest: the sample then ends in the first round, by the first test or (top layer) by
//! the second, and is `-x_i / 2`, exact in floating point. The top layer's `x_{i+1}` is 0: its
//! draws always go to `rand_distr`.
//!
//! This mirrors how `rand_distr` 0.5 maps a draw to a layer and a `u`; the tests below compare
//! the fast path with `StandardNormal` bit for bit, so an upgrade that changes it fails them.

use rand::Rng;
use rand_core::RngCore;
use rand_distr::StandardNormal;
use std::sync::LazyLock;

/// Layers of the ziggurat (the low 8 bits of a draw).
const LAYERS: usize = 256;

/// Bits of `u = -1/2` in the ziggurat's mantissa (`[2, 4)` minus 3): mantissa `2^50`.
const HALF: u64 = 1 << 50;

/// The layer table: `x[i]` scales `u`, and `limit[i] = x_{i+1}` (0 for the top layer) bounds the
/// accepted `|u x_i|`.
pub(super) struct Ziggurat {
    x: [f64; LAYERS],
    limit: [f64; LAYERS],
}

/// The table, read from `rand_distr` on first use.
pub(super) static ZIGGURAT: LazyLock<Ziggurat> = LazyLock::new(Ziggurat::read);

impl Ziggurat {
    /// `StandardNormal`'s result for a draw of `bits` if its first test accepts it.
    #[inline(always)]
    pub(super) fn fast(&self, bits: u64) -> Option<f64> {
        let i = (bits & 0xff) as usize;
        // `u` in [-1, 1): the top 52 bits as the mantissa of a number in [2, 4), minus 3.
        let u = f64::from_bits((1024 << 52) | (bits >> 12)) - 3.0;
        let x = u * self.x[i];
        (x.abs() < self.limit[i]).then_some(x)
    }

    /// The tables `x` and `limit`, for [`super::avx2`]'s lanes.
    #[cfg(target_arch = "x86_64")]
    pub(super) fn tables(&self) -> (&[f64; LAYERS], &[f64; LAYERS]) {
        (&self.x, &self.limit)
    }

    fn read() -> Self {
        let x = std::array::from_fn(|i| -2.0 * probe(i));
        let limit = std::array::from_fn(|i| if i + 1 < LAYERS { x[i + 1] } else { 0.0 });
        Ziggurat { x, limit }
    }
}

/// `StandardNormal`'s sample `-x_layer / 2`, from the draw `u = -1/2` in `layer` followed by
/// the largest draw, which passes the second test of every layer but the bottom one (whose
/// first test passes).
fn probe(layer: usize) -> f64 {
    let mut draws = Probe {
        next: [(HALF << 12) | layer as u64, u64::MAX].into_iter(),
    };
    draws.sample(StandardNormal)
}

/// The two draws of a [`probe`].
struct Probe {
    next: std::array::IntoIter<u64, 2>,
}

impl RngCore for Probe {
    fn next_u32(&mut self) -> u32 {
        self.next_u64() as u32
    }

    fn next_u64(&mut self) -> u64 {
        self.next
            .next()
            .expect("rand_distr's ziggurat asked for a third draw")
    }

    fn fill_bytes(&mut self, dst: &mut [u8]) {
        rand_core::impls::fill_bytes_via_next(self, dst)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::PairRng;

    /// Every layer is read, and the widths are those of the ZIGNOR table
    /// (Doornik 2005): `x_0 = v / f(r)` with `r = 3.654152885361009`, `v = 0.00492867323399`,
    /// `x_1 = r`, decreasing to the top.
    #[test]
    fn the_table_is_the_zignor_table() {
        let z = &*ZIGGURAT;
        let r: f64 = 3.654_152_885_361_009;
        let v: f64 = 0.004_928_673_233_99;
        assert!(
            (z.x[0] - v / (-0.5 * r * r).exp()).abs() < 1e-9,
            "x_0 = {}",
            z.x[0]
        );
        assert_eq!(z.x[1], r);
        assert!(z.x.windows(2).all(|w| w[0] > w[1] && w[1] > 0.0));
        assert!(z.limit[..LAYERS - 1]
            .iter()
            .zip(&z.x[1..])
            .all(|(l, x)| l == x));
        assert_eq!(z.limit[LAYERS - 1], 0.0);
    }

    /// On a million Philox draws the fast path, where it answers, gives rand_distr's bits, and
    /// it answers at the rate of the first test, the mean of `x_{i+1} / x_i` over the layers
    /// (about 98.5 %), within 5 binomial standard deviations (6e-4).
    #[test]
    fn the_fast_path_is_rand_distr_where_it_answers() {
        let z = &*ZIGGURAT;
        let mut answered = 0;
        let n = 1_000_000;
        for k in 0..n {
            let bits = PairRng::new(5, k, 1, 2, 3).next_u64();
            let want: f64 = PairRng::new(5, k, 1, 2, 3).sample(StandardNormal);
            if let Some(x) = z.fast(bits) {
                assert_eq!(x.to_bits(), want.to_bits(), "draw {bits:#x}");
                answered += 1;
            }
        }
        let rate = answered as f64 / n as f64;
        let p = z.limit.iter().zip(&z.x).map(|(l, x)| l / x).sum::<f64>() / LAYERS as f64;
        let tolerance = 5.0 * (p * (1.0 - p) / n as f64).sqrt();
        assert!(
            (rate - p).abs() < tolerance,
            "rate {rate}, expected {p} +- {tolerance}"
        );
    }
}
