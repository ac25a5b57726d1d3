//! Arithmetic on one `f64` or on four in an AVX2 register ([`F64x4`]), so that a formula is
//! written once for both and computes the same numbers in every lane: each operation is one
//! IEEE operation, rounded once, and none is contracted into a multiply-add. Written by hand:
//! the portable SIMD of the standard library is not stable, and the SIMD crates of the
//! ecosystem (`wide`) choose the instruction set when the crate is compiled, while this binary
//! chooses at run time; the pair sweeps need only these few operations. Where the CPU has no
//! AVX2 the same formulas run on `f64`.
//!
//! The operations are `#[inline(always)]` functions around the intrinsics. They become single
//! instructions only where they are inlined into a function compiled with AVX2 (the pair
//! loops inside [`crate::avx2::with_avx2`]); the intrinsics inline there because the caller has
//! the feature.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// One `f64` or a vector of them.
pub(crate) trait Lanes:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// `x` in every lane. `self` only vouches that such a value can exist (for [`F64x4`]:
    /// that the CPU has AVX2); its lanes are not read.
    fn splat(self, x: f64) -> Self;
    /// `max(x, 0)` per lane as `f64::max` gives it (0 for NaN).
    fn max_zero(self) -> Self;
    fn sqrt(self) -> Self;
}

impl Lanes for f64 {
    #[inline(always)]
    fn splat(self, x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn max_zero(self) -> Self {
        self.max(0.0)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
}

#[cfg(target_arch = "x86_64")]
pub(crate) use x86::{F64x4, F64x4x2, Vector};

#[cfg(target_arch = "x86_64")]
mod x86 {
    use super::Lanes;
    use crate::avx2::Avx2;
    use std::arch::x86_64::*;
    use std::ops::{Add, Div, Mul, Neg, Sub};

    /// `N` lanes of `f64` in vector registers: what the vectorised `expm1` needs besides
    /// [`Lanes`]. A value exists only on a CPU with AVX2 ([`Vector::from_fn`] takes the proof,
    /// [`Avx2`]), so the other operations are safe.
    pub(crate) trait Vector<const N: usize>: Lanes {
        /// Lane `l` set to `f(l)`, built in registers: values stored one by one and loaded
        /// as one (a load of an array made in place) cannot be forwarded from the stores, and
        /// the load waits until they reach the cache.
        fn from_fn(avx2: Avx2, f: impl Fn(usize) -> f64) -> Self;
        fn to_array(self) -> [f64; N];
        /// Whether every lane lies in `lo..=hi` (false for NaN).
        fn within(self, lo: f64, hi: f64) -> bool;
        /// Per lane `if self > x { yes } else { no }`.
        fn above_select(self, x: f64, yes: Self, no: Self) -> Self;
        /// Per lane `trunc(x)`, rounded towards zero.
        fn trunc(self) -> Self;
        /// Per lane the bits shifted left by 52, as `f64::from_bits(x.to_bits() << 52)`.
        fn shift_bits_left_52(self) -> Self;
    }

    /// Four `f64` in an AVX2 register.
    #[derive(Clone, Copy)]
    pub(crate) struct F64x4(__m256d);

    impl Vector<4> for F64x4 {
        #[inline(always)]
        fn from_fn(_: Avx2, f: impl Fn(usize) -> f64) -> Self {
            // SAFETY: AVX is part of AVX2, which the CPU has (`Avx2`).
            F64x4(unsafe { _mm256_set_pd(f(3), f(2), f(1), f(0)) })
        }

        #[inline(always)]
        fn to_array(self) -> [f64; 4] {
            let mut out = [0.0; 4];
            // SAFETY: a value exists only with AVX2 (`from_fn`); the store is unaligned.
            unsafe { _mm256_storeu_pd(out.as_mut_ptr(), self.0) };
            out
        }

        #[inline(always)]
        fn within(self, lo: f64, hi: f64) -> bool {
            // SAFETY: as for `to_array`.
            unsafe {
                let above = _mm256_cmp_pd::<_CMP_GE_OQ>(self.0, _mm256_set1_pd(lo));
                let below = _mm256_cmp_pd::<_CMP_LE_OQ>(self.0, _mm256_set1_pd(hi));
                _mm256_movemask_pd(_mm256_and_pd(above, below)) == 0b1111
            }
        }

        #[inline(always)]
        fn above_select(self, x: f64, yes: Self, no: Self) -> Self {
            // SAFETY: as for `to_array`.
            unsafe {
                let mask = _mm256_cmp_pd::<_CMP_GT_OQ>(self.0, _mm256_set1_pd(x));
                F64x4(_mm256_blendv_pd(no.0, yes.0, mask))
            }
        }

        #[inline(always)]
        fn trunc(self) -> Self {
            // SAFETY: as for `to_array`.
            F64x4(unsafe { _mm256_round_pd::<{ _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC }>(self.0) })
        }

        #[inline(always)]
        fn shift_bits_left_52(self) -> Self {
            // SAFETY: as for `to_array`.
            unsafe {
                F64x4(_mm256_castsi256_pd(_mm256_slli_epi64::<52>(
                    _mm256_castpd_si256(self.0),
                )))
            }
        }
    }

    /// Eight `f64` in two AVX2 registers (lanes 0 to 3 in the first), each operation on both:
    /// two independent halves, whose chains of dependent operations the CPU overlaps.
    #[derive(Clone, Copy)]
    pub(crate) struct F64x4x2(F64x4, F64x4);

    impl F64x4x2 {
        /// `f` applied to both halves.
        #[inline(always)]
        fn each(self, f: impl Fn(F64x4) -> F64x4) -> Self {
            F64x4x2(f(self.0), f(self.1))
        }

        /// `f` applied to the halves of `self` and `other`.
        #[inline(always)]
        fn with(self, other: Self, f: impl Fn(F64x4, F64x4) -> F64x4) -> Self {
            F64x4x2(f(self.0, other.0), f(self.1, other.1))
        }
    }

    impl Vector<8> for F64x4x2 {
        #[inline(always)]
        fn from_fn(avx2: Avx2, f: impl Fn(usize) -> f64) -> Self {
            F64x4x2(F64x4::from_fn(avx2, &f), F64x4::from_fn(avx2, |l| f(l + 4)))
        }

        #[inline(always)]
        fn to_array(self) -> [f64; 8] {
            let (low, high) = (self.0.to_array(), self.1.to_array());
            std::array::from_fn(|l| if l < 4 { low[l] } else { high[l - 4] })
        }

        #[inline(always)]
        fn within(self, lo: f64, hi: f64) -> bool {
            self.0.within(lo, hi) & self.1.within(lo, hi)
        }

        #[inline(always)]
        fn above_select(self, x: f64, yes: Self, no: Self) -> Self {
            F64x4x2(
                self.0.above_select(x, yes.0, no.0),
                self.1.above_select(x, yes.1, no.1),
            )
        }

        #[inline(always)]
        fn trunc(self) -> Self {
            self.each(F64x4::trunc)
        }

        #[inline(always)]
        fn shift_bits_left_52(self) -> Self {
            self.each(F64x4::shift_bits_left_52)
        }
    }

    /// The binary operators, one intrinsic per lane-wise IEEE operation.
    macro_rules! binary {
        ($($trait:ident $method:ident $intrinsic:ident),*) => {$(
            impl $trait for F64x4 {
                type Output = Self;
                #[inline(always)]
                fn $method(self, other: Self) -> Self {
                    // SAFETY: a value exists only with AVX2 (`from_fn`).
                    F64x4(unsafe { $intrinsic(self.0, other.0) })
                }
            }
        )*};
    }
    binary!(Add add _mm256_add_pd, Sub sub _mm256_sub_pd, Mul mul _mm256_mul_pd, Div div _mm256_div_pd);

    /// The binary operators of [`F64x4x2`], half by half.
    macro_rules! binary_halves {
        ($($trait:ident $method:ident),*) => {$(
            impl $trait for F64x4x2 {
                type Output = Self;
                #[inline(always)]
                fn $method(self, other: Self) -> Self {
                    self.with(other, F64x4::$method)
                }
            }
        )*};
    }
    binary_halves!(Add add, Sub sub, Mul mul, Div div);

    impl Neg for F64x4 {
        type Output = Self;
        /// The sign bit flipped, as `-x` on `f64`.
        #[inline(always)]
        fn neg(self) -> Self {
            // SAFETY: as for the binary operators.
            F64x4(unsafe { _mm256_xor_pd(self.0, _mm256_set1_pd(-0.0)) })
        }
    }

    impl Neg for F64x4x2 {
        type Output = Self;
        #[inline(always)]
        fn neg(self) -> Self {
            self.each(F64x4::neg)
        }
    }

    impl Lanes for F64x4x2 {
        #[inline(always)]
        fn splat(self, x: f64) -> Self {
            self.each(|half| half.splat(x))
        }
        #[inline(always)]
        fn max_zero(self) -> Self {
            self.each(F64x4::max_zero)
        }
        #[inline(always)]
        fn sqrt(self) -> Self {
            self.each(F64x4::sqrt)
        }
    }

    impl Lanes for F64x4 {
        #[inline(always)]
        fn splat(self, x: f64) -> Self {
            // SAFETY: `self` exists, so the CPU has AVX2 (`from_fn`).
            F64x4(unsafe { _mm256_set1_pd(x) })
        }
        #[inline(always)]
        fn max_zero(self) -> Self {
            // `maxpd` returns its second operand when either is NaN: 0, as `f64::max`.
            // SAFETY: as for the binary operators.
            F64x4(unsafe { _mm256_max_pd(self.0, _mm256_setzero_pd()) })
        }
        #[inline(always)]
        fn sqrt(self) -> Self {
            // SAFETY: as for the binary operators.
            F64x4(unsafe { _mm256_sqrt_pd(self.0) })
        }
    }

    #[cfg(test)]
    mod tests {
        use super::*;

        /// Every operation of `V` on lanes `a` and `b` equals the scalar one in every lane.
        fn every_operation_is_the_scalar_one<const N: usize, V: Vector<N>>(
            avx2: Avx2,
            a: [f64; N],
            b: [f64; N],
        ) {
            let (x, y) = (V::from_fn(avx2, |l| a[l]), V::from_fn(avx2, |l| b[l]));
            // Bits, but any NaN as one: Rust leaves NaN payloads and signs unspecified (a
            // constant-folded 0 / 0 and the CPU's differ in the sign).
            let bits = |x: f64| {
                if x.is_nan() {
                    f64::NAN.to_bits()
                } else {
                    x.to_bits()
                }
            };
            let lanes = |v: V| v.to_array().map(bits);
            let each = |f: fn(f64, f64) -> f64| std::array::from_fn(|l| bits(f(a[l], b[l])));
            assert_eq!(lanes(x + y), each(|a, b| a + b));
            assert_eq!(lanes(x - y), each(|a, b| a - b));
            assert_eq!(lanes(x * y), each(|a, b| a * b));
            assert_eq!(lanes(x / y), each(|a, b| a / b));
            assert_eq!(lanes(-x), each(|a, _| -a));
            assert_eq!(lanes(x.splat(2.5)), each(|_, _| 2.5));
            assert_eq!(lanes(x.max_zero()), each(|a, _| a.max(0.0)));
            assert_eq!(lanes(x.sqrt()), each(|a, _| a.sqrt()));
            assert_eq!(lanes(x.trunc()), each(|a, _| a.trunc()));
            assert_eq!(
                lanes(x.shift_bits_left_52()),
                each(|a, _| f64::from_bits(a.to_bits() << 52))
            );
            assert_eq!(
                lanes(x.above_select(0.0, x, y)),
                each(|a, b| if a > 0.0 { a } else { b })
            );
            assert!(!x.within(-10.0, 10.0));
            let inside = V::from_fn(avx2, |l| [0.0, -1.0, -40.0, -0.5][l % 4]);
            assert!(inside.within(-40.0, 0.0));
            for lane in 0..N {
                // One lane at a time out of range.
                let c: [f64; N] = std::array::from_fn(|l| if l == lane { 1.0 } else { -0.5 });
                assert!(!V::from_fn(avx2, |l| c[l]).within(-40.0, 0.0));
            }
        }

        #[test]
        fn every_operation_is_the_scalar_one_in_every_lane() {
            let Some(avx2) = Avx2::detect() else {
                return;
            };
            let a = [
                1.5,
                -0.0,
                f64::NAN,
                3.0e-310,
                2.0,
                -7.5,
                0.25,
                -f64::INFINITY,
            ];
            let b = [-2.25, 0.0, 7.0, f64::INFINITY, -1.0, 4.0, f64::NAN, -0.0];
            every_operation_is_the_scalar_one::<4, F64x4>(
                avx2,
                std::array::from_fn(|l| a[l]),
                std::array::from_fn(|l| b[l]),
            );
            every_operation_is_the_scalar_one::<8, F64x4x2>(avx2, a, b);
        }
    }
}
