//! Counter-based pair random numbers.
//!
//! Every random number a pair receives is a pure function of the key
//! `(seed, step, stream, min(i, j), max(i, j))` of the particle ids `i`, `j` ([`crate::System::ids`]):
//! it does not depend on where the particles are stored, on the layout of the pair
//! list, on when the list was built, or on the number of threads. The generator is
//! Philox4x32-10 (Salmon, Moraes, Dror and Shaw, "Parallel random numbers: as easy as 1, 2, 3",
//! SC 2011), written here by hand because no maintained crate of the rand family provides a
//! keyed counter-based generator; its output is checked against the published known-answer
//! vectors of Random123. Standard normals come from `rand_distr::StandardNormal` (ziggurat)
//! drawing on the Philox blocks of the key. The pair passes draw the normals of a run of pairs
//! at once with [`pair_normals`], which computes the first blocks of several pairs in vector
//! registers, runs the ziggurat's first test inline and gives the same numbers as
//! [`pair_normal`].
//!
//! Counter layout (128 bits): `[i, j, step low 32 bits, step bits 32..47 << 16 | stream << 8 |
//! block]`, key = seed. Steps up to 2^48, 256 streams per step, 256 blocks of 128 bits per pair.

use rand::Rng;
use rand_core::RngCore;
use rand_distr::StandardNormal;
use ziggurat::ZIGGURAT;

#[cfg(target_arch = "x86_64")]
mod avx2;
mod ziggurat;

const M0: u32 = 0xD251_1F53;
const M1: u32 = 0xCD9E_8D57;
const W0: u32 = 0x9E37_79B9;
const W1: u32 = 0xBB67_AE85;

#[inline(always)]
fn mulhilo(a: u32, b: u32) -> (u32, u32) {
    let p = (a as u64) * (b as u64);
    ((p >> 32) as u32, p as u32)
}

/// Philox4x32 with 10 rounds: a bijection of the 128-bit counter under a 64-bit key.
#[inline(always)]
pub fn philox4x32_10(mut ctr: [u32; 4], key: [u32; 2]) -> [u32; 4] {
    let mut k = key;
    for round in 0..10 {
        if round > 0 {
            k[0] = k[0].wrapping_add(W0);
            k[1] = k[1].wrapping_add(W1);
        }
        let (hi0, lo0) = mulhilo(M0, ctr[0]);
        let (hi1, lo1) = mulhilo(M1, ctr[2]);
        ctr = [hi1 ^ ctr[1] ^ k[0], lo1, hi0 ^ ctr[3] ^ k[1], lo0];
    }
    ctr
}

/// Pairs whose first Philox blocks [`pair_normals`] computes together.
const LANES: usize = 16;

/// Philox4x32-10 on `LANES` counters at once (`ctr[w][l]`: word `w` of lane `l`), lane by
/// lane: the portable form, which the compiler vectorises only in part.
#[inline(always)]
fn philox_lanes(ctr: &mut [[u32; LANES]; 4], key: [u32; 2]) {
    let mut k = key;
    for round in 0..10 {
        if round > 0 {
            k[0] = k[0].wrapping_add(W0);
            k[1] = k[1].wrapping_add(W1);
        }
        // Lane by lane over four arrays: the indexed form is the one the compiler vectorises.
        #[allow(clippy::needless_range_loop)]
        for l in 0..LANES {
            let (hi0, lo0) = mulhilo(M0, ctr[0][l]);
            let (hi1, lo1) = mulhilo(M1, ctr[2][l]);
            let (c1, c3) = (ctr[1][l], ctr[3][l]);
            ctr[0][l] = hi1 ^ c1 ^ k[0];
            ctr[1][l] = lo1;
            ctr[2][l] = hi0 ^ c3 ^ k[1];
            ctr[3][l] = lo0;
        }
    }
}

/// `out[k] = pair_normal(seed, step, stream, i, j)` for `(i, j) = pair(k)`: the first Philox
/// blocks of `LANES` pairs at a time are computed together, then each pair's first draw goes
/// through the ziggurat's first test inline (module `ziggurat`); the 1.5 % it rejects are
/// sampled by `rand_distr` on the pair's [`PairRng`], which draws further blocks. Bitwise the
/// same as [`pair_normal`]. On x86_64 CPUs with AVX2 (detected at run time) all but the
/// closure's calls and the rejected draws run in AVX2 registers (module `avx2`).
pub fn pair_normals(
    seed: u64,
    step: u64,
    stream: u8,
    pair: impl Fn(usize) -> (u32, u32),
    out: &mut [f64],
) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the feature was detected.
        return unsafe { avx2::pair_normals(seed, step, stream, pair, out) };
    }
    pair_normals_portable(seed, step, stream, pair, out)
}

/// [`pair_normals`] on any CPU: the lanes are arrays, which the compiler vectorises in part.
fn pair_normals_portable(
    seed: u64,
    step: u64,
    stream: u8,
    pair: impl Fn(usize) -> (u32, u32),
    out: &mut [f64],
) {
    let head = PairRng::new(seed, step, stream, 0, 1);
    let zig = &*ZIGGURAT;
    // Words 2 and 3 of the counters (step, stream, block 0) are the same for every pair.
    let mut ctr = [
        [0; LANES],
        [0; LANES],
        [head.ctr[2]; LANES],
        [head.ctr[3]; LANES],
    ];
    for (b, block) in out.chunks_mut(LANES).enumerate() {
        // Lane by lane over two arrays, the indexed form (as in `philox_lanes`).
        #[allow(clippy::needless_range_loop)]
        for l in 0..LANES {
            let (i, j) = if l < block.len() {
                pair(b * LANES + l)
            } else {
                (0, 1)
            };
            (ctr[0][l], ctr[1][l]) = (i.min(j), i.max(j));
        }
        let mut first = ctr;
        philox_lanes(&mut first, head.key);
        for (l, z) in block.iter_mut().enumerate() {
            // The first draw of the pair's stream, as `next_u64` reads it.
            let bits = u64::from(first[0][l]) | (u64::from(first[1][l]) << 32);
            *z = zig.fast(bits).unwrap_or_else(|| {
                head.rejected(ctr[0][l], ctr[1][l], [0, 1, 2, 3].map(|w| first[w][l]))
            });
        }
    }
}

/// The random stream of one pair in one sweep of one step: an `RngCore` over consecutive
/// Philox blocks of the pair's counter.
pub struct PairRng {
    ctr: [u32; 4],
    key: [u32; 2],
    /// The current block as two 64-bit words (`w0 | w1 << 32`, `w2 | w3 << 32`), so that the
    /// usual draw, one `u64`, is one aligned load of what one store wrote.
    buf: [u64; 2],
    /// 32-bit words of the block used, 0 to 4.
    used: usize,
}

impl PairRng {
    /// The stream of pair `(i, j)` (either order) in `stream` of `step`, under `seed`.
    #[inline(always)]
    pub fn new(seed: u64, step: u64, stream: u8, i: u32, j: u32) -> Self {
        let tag = (((step >> 32) as u32 & 0xFFFF) << 16) | ((stream as u32) << 8);
        PairRng {
            ctr: [0, 0, step as u32, tag],
            key: [seed as u32, (seed >> 32) as u32],
            buf: [0; 2],
            used: 4,
        }
        .of_ordered(i.min(j), i.max(j))
    }

    /// The stream of pair `(lo, hi)`, `lo < hi`, in the same step, stream and seed, from its
    /// first block.
    #[inline(always)]
    fn of_ordered(&self, lo: u32, hi: u32) -> Self {
        PairRng {
            ctr: [lo, hi, self.ctr[2], self.ctr[3] & !0xFF],
            used: 4,
            ..*self
        }
    }

    /// The normal of pair `(lo, hi)`, `lo < hi`, in the same step, stream and seed, whose first
    /// block `first` is already computed and whose first draw the ziggurat's first test
    /// rejected: `rand_distr` samples it from that block on.
    #[inline(always)]
    fn rejected(&self, lo: u32, hi: u32, first: [u32; 4]) -> f64 {
        let mut rng = self.of_ordered(lo, hi);
        rng.preload(first);
        rng.normal()
    }

    /// The next block. Rare in the pair passes, which preload the first block of every pair:
    /// kept out of line, so that the ziggurat's fast path does not carry the key schedule
    /// (a build where it was inlined hoisted the schedule into every draw, 116 instead of 47
    /// instructions per normal).
    #[cold]
    #[inline(never)]
    fn refill(&mut self) {
        self.preload(philox4x32_10(self.ctr, self.key));
    }

    /// Take `block`, the Philox output of the current counter, as the next four words.
    #[inline(always)]
    fn preload(&mut self, block: [u32; 4]) {
        let [w0, w1, w2, w3] = block.map(u64::from);
        self.buf = [w0 | (w1 << 32), w2 | (w3 << 32)];
        // Next block: the low byte of the last word counts blocks (wraps after 256).
        self.ctr[3] = (self.ctr[3] & !0xFF) | ((self.ctr[3].wrapping_add(1)) & 0xFF);
        self.used = 0;
    }

    /// A standard normal variate.
    #[inline(always)]
    pub fn normal(&mut self) -> f64 {
        self.sample(StandardNormal)
    }
}

impl RngCore for PairRng {
    #[inline(always)]
    fn next_u32(&mut self) -> u32 {
        if self.used == 4 {
            self.refill();
        }
        let x = (self.buf[self.used / 2] >> (32 * (self.used % 2))) as u32;
        self.used += 1;
        x
    }

    #[inline(always)]
    fn next_u64(&mut self) -> u64 {
        if self.used > 2 {
            self.refill();
        }
        let x = match self.used {
            0 => self.buf[0],
            1 => (self.buf[0] >> 32) | (self.buf[1] << 32),
            _ => self.buf[1],
        };
        self.used += 2;
        x
    }

    fn fill_bytes(&mut self, dst: &mut [u8]) {
        for chunk in dst.chunks_mut(4) {
            let b = self.next_u32().to_le_bytes();
            chunk.copy_from_slice(&b[..chunk.len()]);
        }
    }
}

/// One standard normal for pair `(i, j)` in `stream` of `step`.
#[inline(always)]
pub fn pair_normal(seed: u64, step: u64, stream: u8, i: u32, j: u32) -> f64 {
    PairRng::new(seed, step, stream, i, j).normal()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn philox_known_answers() {
        // Random123 kat_vectors, "philox4x32 10" lines: counter, key, expected.
        let kat: [([u32; 4], [u32; 2], [u32; 4]); 3] = [
            (
                [0; 4],
                [0; 2],
                [0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8],
            ),
            (
                [u32::MAX; 4],
                [u32::MAX; 2],
                [0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd],
            ),
            (
                [0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344],
                [0xa4093822, 0x299f31d0],
                [0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1],
            ),
        ];
        for (ctr, key, want) in kat {
            assert_eq!(philox4x32_10(ctr, key), want);
        }
    }

    #[test]
    fn symmetric_in_pair_and_distinct_across_keys() {
        let a = pair_normal(7, 3, 1, 10, 20);
        assert_eq!(a, pair_normal(7, 3, 1, 20, 10));
        assert_ne!(a, pair_normal(7, 3, 2, 10, 20));
        assert_ne!(a, pair_normal(7, 4, 1, 10, 20));
        assert_ne!(a, pair_normal(8, 3, 1, 10, 20));
        assert_ne!(a, pair_normal(7, 3, 1, 10, 21));
        assert_ne!(
            pair_normal(7, 1 << 32, 1, 10, 20),
            pair_normal(7, 0, 1, 10, 20)
        );
    }

    #[test]
    fn batched_normals_are_the_pair_normals() {
        // 1e5 pairs reach the ziggurat's slow path (about 1 % of draws) many times; lengths
        // that are not multiples of the lanes leave partial blocks.
        let key = |k: usize| ((k as u32).wrapping_mul(7919), k as u32 / 3);
        for n in [0, 1, LANES - 1, LANES + 3, 100_000] {
            let mut out = vec![f64::NAN; n];
            pair_normals(11, n as u64, 2, key, &mut out);
            let mut portable = vec![f64::NAN; n];
            pair_normals_portable(11, n as u64, 2, key, &mut portable);
            for (k, (&z, &zp)) in out.iter().zip(&portable).enumerate() {
                let (i, j) = key(k);
                let want = pair_normal(11, n as u64, 2, i, j).to_bits();
                assert_eq!((z.to_bits(), zp.to_bits()), (want, want), "pair {k} of {n}");
            }
        }
    }

    #[test]
    fn normals_have_unit_moments() {
        // 2e5 samples: the standard error of the mean is 0.0022 and of the variance 0.0032,
        // so 0.015 is about five standard errors.
        let n = 200_000u32;
        let (mut s1, mut s2) = (0.0, 0.0);
        for k in 0..n {
            let x = pair_normal(42, k as u64, 0, k, k + 1);
            s1 += x;
            s2 += x * x;
        }
        let mean = s1 / n as f64;
        let var = s2 / n as f64 - mean * mean;
        assert!(mean.abs() < 0.015, "mean {mean}");
        assert!((var - 1.0).abs() < 0.015, "variance {var}");
    }
}
