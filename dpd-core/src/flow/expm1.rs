//! `exp(x) - 1` inlined into the pair sweeps.
//!
//! The O and T sweeps need `expm1` once per pair. The C library's, reached through
//! `f64::exp_m1`, is an opaque call: the sweep spills its live registers around it, and the
//! call costs about 10 % of an ABOBA step (measured by putting `x + x^2/2` in its place). No
//! maintained crate offers an inlinable `expm1` (the `libm` crate's is not `#[inline]`), so
//! this one is written here: range reduction by powers of two and a degree-13 Taylor
//! polynomial. Over the arguments of the sweeps (`x <= 0`) it is at most 1 ulp from the C
//! library's on 10^5 arguments from -800 to -1e-300 (tested to 2); other arguments go to the
//! C library. ABOBA, `step_timing 24000 100 1 0.0 aboba`, alternating builds: about 3 %
//! faster per step.

use crate::lanes::Lanes;
#[cfg(target_arch = "x86_64")]
use crate::lanes::Vector;

/// `ln 2` split so that `k * LN2_HI` is exact for `|k| < 2^20`, and the remainder.
const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);

/// `2^52 + 1023`: an integer `k` in `-1023..=1024` added to it is exact, with `1023 + k` in the
/// low mantissa bits.
#[cfg(target_arch = "x86_64")]
const EXPONENT_BIAS: f64 = 4_503_599_627_371_519.0;

/// `1/n!` for `n = 2..=13`.
const TAYLOR: [f64; 12] = [
    1.0 / 2.0,
    1.0 / 6.0,
    1.0 / 24.0,
    1.0 / 120.0,
    1.0 / 720.0,
    1.0 / 5_040.0,
    1.0 / 40_320.0,
    1.0 / 362_880.0,
    1.0 / 3_628_800.0,
    1.0 / 39_916_800.0,
    1.0 / 479_001_600.0,
    1.0 / 6_227_020_800.0,
];

/// `exp(r) - 1` for `|r| <= 0.35`: the truncation error `r^14 / 14!` is below `5e-18`. The
/// polynomial is evaluated by Estrin's scheme (pairs, then powers `r^2`, `r^4`, `r^8`), whose
/// dependency chain is a third of Horner's.
#[inline(always)]
fn small<L: Lanes>(r: L) -> L {
    let c = |k: usize| r.splat(TAYLOR[k]);
    let r2 = r * r;
    let r4 = r2 * r2;
    let r8 = r4 * r4;
    // Written out: `[T; N]::map` is not always inlined (it was a call in the ABOBA profile).
    let pair = |k: usize| c(k) + c(k + 1) * r;
    let b0 = pair(0) + pair(2) * r2;
    let b1 = pair(4) + pair(6) * r2;
    let b2 = pair(8) + pair(10) * r2;
    r + r2 * ((b0 + b1 * r4) + b2 * r8)
}

/// `exp(x) - 1`, accurate to a few ulp relative to the result also for `x -> 0`.
#[inline(always)]
pub(crate) fn expm1(x: f64) -> f64 {
    if x > -0.25 && x <= 0.0 {
        return small(x);
    }
    if !(-40.0..=0.0).contains(&x) {
        // exp(-40) is below half an ulp of 1: the result rounds to -1. Positive and NaN
        // arguments (never from the sweeps) go to the C library.
        return if x < -40.0 { -1.0 } else { x.exp_m1() };
    }
    // x = k ln 2 + r with |r| <= ln 2 / 2 and k in -58..=0 (the conversion truncates towards
    // zero: k = ceil(x log2 e - 1/2)); exp(x) - 1 = 2^k (exp(r) - 1) + (2^k - 1).
    let k = (x * std::f64::consts::LOG2_E - 0.5) as i64;
    let kf = k as f64;
    let r = (x - kf * LN2_HI) - kf * LN2_LO;
    let two_k = f64::from_bits(((1023 + k) as u64) << 52);
    two_k * small(r) + (two_k - 1.0)
}

/// [`expm1`] of `N` arguments in `[-40, 0]` (checked by the caller: [`Vector::within`]), bit
/// for bit. Its two branches there become a select: one polynomial, on `x` itself or on its
/// reduced argument. `k` and `2^k` are computed in floating point: `trunc` is the conversion's
/// truncation (`+ 0` turns its -0 into the conversion's 0), and adding `2^52 + 1023` leaves
/// `1023 + k` in the low bits of the sum, which a shift moves to the exponent.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn expm1_within<const N: usize, V: Vector<N>>(x: V) -> V {
    let splat = |c| x.splat(c);
    let kf = (x * splat(std::f64::consts::LOG2_E) - splat(0.5)).trunc() + splat(0.0);
    let r = (x - kf * splat(LN2_HI)) - kf * splat(LN2_LO);
    let two_k = (kf + splat(EXPONENT_BIAS)).shift_bits_left_52();
    let p = small(x.above_select(-0.25, x, r));
    x.above_select(-0.25, p, two_k * p + (two_k - splat(1.0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance in units in the last place between `a` and `b` (same sign assumed; the two
    /// zeros are equal).
    fn ulps(a: f64, b: f64) -> u64 {
        if a == b {
            return 0;
        }
        (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs()
    }

    #[test]
    fn within_two_ulp_of_the_c_library_for_non_positive_arguments() {
        let mut worst = (0, 0.0);
        let mut x = -1e-300;
        while x > -800.0 {
            for t in [x, x * 1.000_000_7, x * 1.37, x * 2.9] {
                let d = ulps(expm1(t), t.exp_m1());
                if d > worst.0 {
                    worst = (d, t);
                }
            }
            x *= 1.01;
        }
        // Uniformly around the branch points.
        for k in 0..200_000 {
            let t = -(k as f64) * 2e-4;
            let d = ulps(expm1(t), t.exp_m1());
            if d > worst.0 {
                worst = (d, t);
            }
        }
        println!("worst: {} ulp at x = {:e}", worst.0, worst.1);
        assert!(worst.0 <= 2, "{} ulp at x = {:e}", worst.0, worst.1);
    }

    #[cfg(target_arch = "x86_64")]
    #[test]
    fn lanes_equal_the_scalar_function_bit_for_bit() {
        use crate::avx2::Avx2;
        use crate::lanes::{F64x4, F64x4x2};
        let Some(avx2) = Avx2::detect() else {
            return;
        };
        // Both branches, their boundary and the ends of the range.
        let mut args = vec![
            0.0,
            -0.0,
            -0.25,
            -0.25f64.next_down(),
            -0.25f64.next_up(),
            -40.0,
        ];
        let mut x = -1e-300;
        while x > -40.0 {
            args.extend([x, x * 1.37, x * 2.9]);
            x *= 1.003;
        }
        args.extend((0..97_000).map(|k| -(k as f64) * 4.1e-4));
        // Four lanes in one register and eight in two.
        for lanes in args.chunks(8) {
            let lanes: [f64; 8] =
                std::array::from_fn(|l| lanes.get(l).map_or(-1.0, |x| x.max(-40.0)));
            let want = lanes.map(|x| expm1(x).to_bits());
            let (x4, x8) = (
                F64x4::from_fn(avx2, |l| lanes[l]),
                F64x4x2::from_fn(avx2, |l| lanes[l]),
            );
            assert!(x4.within(-40.0, 0.0) && x8.within(-40.0, 0.0));
            assert_eq!(
                expm1_within(x8).to_array().map(f64::to_bits),
                want,
                "{lanes:?}"
            );
            assert_eq!(
                expm1_within(x4).to_array().map(f64::to_bits),
                want[..4],
                "{lanes:?}"
            );
        }
    }

    #[test]
    fn edges() {
        assert_eq!(LN2_HI + LN2_LO, std::f64::consts::LN_2);
        assert_eq!(expm1(0.0), 0.0);
        assert_eq!(expm1(-1e-300), -1e-300);
        assert_eq!(expm1(f64::NEG_INFINITY), -1.0);
        assert_eq!(expm1(-1e6), -1.0);
        assert_eq!(expm1(0.5), 0.5f64.exp_m1());
        assert!(expm1(f64::NAN).is_nan());
    }
}
