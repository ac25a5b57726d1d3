//! [`super::pair_normals`] in AVX2 registers, written with intrinsics.
//!
//! Per block of [`LANES`] pairs: the particle ids come from the caller's closure, one pair at
//! a time; ordering them, the ten Philox rounds and the ziggurat's first test run on eight
//! (ids, Philox) or four (the 64-bit draws and the normals) lanes per instruction. A lane the
//! first test rejects (about 1.5 %) goes to `rand_distr` on the pair's [`PairRng`], preloaded
//! with the block already computed, as in the portable form. The integer and floating-point
//! operations are those of [`super::pair_normal`], so the numbers are bitwise the same.
//!
//! In the portable form the ordering, the draws' assembly and the first test were scalar,
//! about 30 of the 79 instructions per normal that an ABOBA step of the stiff melt spent
//! (callgrind, N = 24 000).

use super::ziggurat::Ziggurat;
use super::{PairRng, LANES, M0, M1, W0, W1, ZIGGURAT};
use std::arch::x86_64::*;

/// Groups of eight 32-bit lanes in a block.
const GROUPS: usize = LANES / 8;

/// The Philox words of a block: `[group][word]`, lane `8 g + l` in element `l` of group `g`.
type Blocks = [[__m256i; 4]; GROUPS];

/// [`super::pair_normals`] on a CPU with AVX2.
///
/// # Safety
/// The CPU must support AVX2.
#[target_feature(enable = "avx2")]
pub(super) unsafe fn pair_normals(
    seed: u64,
    step: u64,
    stream: u8,
    pair: impl Fn(usize) -> (u32, u32),
    out: &mut [f64],
) {
    let head = PairRng::new(seed, step, stream, 0, 1);
    let zig = &*ZIGGURAT;
    // Words 2 and 3 of the counters (step, stream, block 0) are the same for every pair.
    let (w2, w3) = (
        _mm256_set1_epi32(head.ctr[2] as i32),
        _mm256_set1_epi32(head.ctr[3] as i32),
    );
    let keys = RoundKeys::new(head.key);
    let mut ids = [[0u32; LANES]; 2];
    let mut first = [[0u32; LANES]; 4];
    let mut normals = [0.0; LANES];
    for (b, block) in out.chunks_mut(LANES).enumerate() {
        let pair = |l| pair(b * LANES + l);
        // Lane by lane over two arrays, the indexed form (as in the portable `philox_lanes`);
        // a full block without the test of the length, which the compiler then unrolls.
        #[allow(clippy::needless_range_loop)]
        if block.len() == LANES {
            for l in 0..LANES {
                (ids[0][l], ids[1][l]) = pair(l);
            }
        } else {
            for l in 0..LANES {
                (ids[0][l], ids[1][l]) = if l < block.len() { pair(l) } else { (0, 1) };
            }
        }
        let counters: Blocks = std::array::from_fn(|g| {
            let (i, j) = (load(&ids[0], g), load(&ids[1], g));
            [_mm256_min_epu32(i, j), _mm256_max_epu32(i, j), w2, w3]
        });
        let blocks = philox(counters, &keys);
        let mut accepted = 0u32;
        for (g, words) in blocks.iter().enumerate() {
            for (w, &v) in words.iter().enumerate() {
                store(&mut first[w], g, v);
            }
            let halves = [
                (
                    _mm256_castsi256_si128(words[0]),
                    _mm256_castsi256_si128(words[1]),
                ),
                (
                    _mm256_extracti128_si256::<1>(words[0]),
                    _mm256_extracti128_si256::<1>(words[1]),
                ),
            ];
            for (h, (w0, w1)) in halves.into_iter().enumerate() {
                // The first draw of each pair's stream, as `next_u64` reads it: `w0 | w1 << 32`.
                let draws = _mm256_or_si256(
                    _mm256_cvtepu32_epi64(w0),
                    _mm256_slli_epi64::<32>(_mm256_cvtepu32_epi64(w1)),
                );
                let (x, answered) = fast4(zig, draws);
                let lane = 8 * g + 4 * h;
                // SAFETY: lanes `lane .. lane + 4` are within `normals` (lane + 4 <= LANES).
                unsafe { _mm256_storeu_pd(normals[lane..lane + 4].as_mut_ptr(), x) };
                accepted |= answered << lane;
            }
        }
        let mut slow = !accepted & ((1u32 << block.len()) - 1);
        while slow != 0 {
            let l = slow.trailing_zeros() as usize;
            slow &= slow - 1;
            let (i, j) = (ids[0][l], ids[1][l]);
            normals[l] = head.rejected(i.min(j), i.max(j), [0, 1, 2, 3].map(|w| first[w][l]));
        }
        match <&mut [f64; LANES]>::try_from(&mut *block) {
            Ok(full) => *full = normals,
            Err(_) => block.copy_from_slice(&normals[..block.len()]),
        }
    }
}

/// The ten round keys of Philox under one key, each in every lane.
struct RoundKeys([[__m256i; 2]; 10]);

impl RoundKeys {
    #[target_feature(enable = "avx2")]
    #[inline]
    fn new(key: [u32; 2]) -> RoundKeys {
        let mut k = key;
        RoundKeys(std::array::from_fn(|round| {
            if round > 0 {
                k[0] = k[0].wrapping_add(W0);
                k[1] = k[1].wrapping_add(W1);
            }
            k.map(|k| _mm256_set1_epi32(k as i32))
        }))
    }
}

/// Lanes `8 g .. 8 g + 8` of `w`.
#[target_feature(enable = "avx2")]
#[inline]
fn load(w: &[u32; LANES], g: usize) -> __m256i {
    let lanes = &w[8 * g..8 * g + 8];
    // SAFETY: `lanes` holds the eight `u32` read.
    unsafe { _mm256_loadu_si256(lanes.as_ptr().cast()) }
}

/// Write `v` to lanes `8 g .. 8 g + 8` of `w`.
#[target_feature(enable = "avx2")]
#[inline]
fn store(w: &mut [u32; LANES], g: usize, v: __m256i) {
    let lanes = &mut w[8 * g..8 * g + 8];
    // SAFETY: `lanes` holds the eight `u32` written.
    unsafe { _mm256_storeu_si256(lanes.as_mut_ptr().cast(), v) }
}

/// Philox4x32-10 of the counters `c` under the key of `keys` ([`super::philox4x32_10`] in every
/// lane).
/// Each group takes per product two `vpmuludq` (even and odd lanes) and shifts and blends that
/// stay within 64-bit lanes (the compiler's own vectorisation of the 32 x 32 -> 64-bit products
/// shuffled lanes across the register halves and computed the low words a second time); the
/// groups are independent, so their dependency chains overlap.
#[target_feature(enable = "avx2")]
#[inline]
fn philox(mut c: Blocks, keys: &RoundKeys) -> Blocks {
    let (m0, m1) = (_mm256_set1_epi32(M0 as i32), _mm256_set1_epi32(M1 as i32));
    for &[k0, k1] in &keys.0 {
        for c in &mut c {
            let (hi0, lo0) = mulhilo8(c[0], m0);
            let (hi1, lo1) = mulhilo8(c[2], m1);
            *c = [
                _mm256_xor_si256(_mm256_xor_si256(hi1, c[1]), k0),
                lo1,
                _mm256_xor_si256(_mm256_xor_si256(hi0, c[3]), k1),
                lo0,
            ];
        }
    }
    c
}

/// `(hi, lo)` of `a * m` in every 32-bit lane.
#[target_feature(enable = "avx2")]
#[inline]
fn mulhilo8(a: __m256i, m: __m256i) -> (__m256i, __m256i) {
    let even = _mm256_mul_epu32(a, m);
    let odd = _mm256_mul_epu32(_mm256_srli_epi64::<32>(a), m);
    let hi = _mm256_blend_epi32::<0b1010_1010>(_mm256_srli_epi64::<32>(even), odd);
    let lo = _mm256_blend_epi32::<0b1010_1010>(even, _mm256_slli_epi64::<32>(odd));
    (hi, lo)
}

/// [`Ziggurat::fast`] of four draws at once: the candidates `u x_i` and a bit per lane (bit
/// `l` for lane `l`) set where the first test accepts; a lane whose bit is clear must be
/// sampled by `rand_distr`.
#[target_feature(enable = "avx2")]
#[inline]
fn fast4(zig: &Ziggurat, bits: __m256i) -> (__m256d, u32) {
    let layer = _mm256_and_si256(bits, _mm256_set1_epi64x(0xff));
    let (x_tab, limit_tab) = zig.tables();
    // SAFETY: every index is below 256 (the low 8 bits of a draw), the tables' length.
    let (x_i, limit) = unsafe {
        (
            _mm256_i64gather_pd::<8>(x_tab.as_ptr(), layer),
            _mm256_i64gather_pd::<8>(limit_tab.as_ptr(), layer),
        )
    };
    let mantissa = _mm256_or_si256(
        _mm256_srli_epi64::<12>(bits),
        _mm256_set1_epi64x(1024 << 52),
    );
    let u = _mm256_sub_pd(_mm256_castsi256_pd(mantissa), _mm256_set1_pd(3.0));
    let x = _mm256_mul_pd(u, x_i);
    let magnitude = _mm256_andnot_pd(_mm256_set1_pd(-0.0), x);
    let inside = _mm256_cmp_pd::<_CMP_LT_OQ>(magnitude, limit);
    (x, _mm256_movemask_pd(inside) as u32)
}
