//! Coefficient fields of the analysis: exact rationals and `f64`.
//!
//! [`Rational`] keeps small values as reduced `i128` fractions and falls back to
//! [`BigRational`] only when an operation would overflow, so that exact analysis of short
//! schemes stays cheap (no heap allocation on the common path).

use std::fmt;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

/// Tolerance of the `f64` analysis, relative to a bound on the magnitude of the quantity tested.
///
/// Callers pass that bound as `scale` to [`Scalar::negligible`]: every word coefficient is a
/// sum of products of stage coefficients, bounded by `max(1, C)^n` for a word of degree `n`
/// (`C` the sum of the absolute stage coefficients). The tolerance is tied to the precision
/// the coefficients are given to: an inexact coefficient is an `f64` (relative error 1.1e-16)
/// or a literal typed to at least 13 significant digits (`lang::APPROXIMATE_DIGITS`, relative
/// error at most 5e-13), and rounding in a few thousand operations adds about 1e-14. So a
/// defect below 1e-12 of the bound cannot be told from the precision of the input, and one
/// above it is real: `x0 + 5e-9` in the triple jump leaves a third-order defect near 4e-10 of
/// the bound (order 2), Yoshida's sixth-order solution typed to 15 digits one near 5e-18
/// (order 6).
pub const FLOAT_TOLERANCE: f64 = 1e-12;

/// A coefficient field: what the truncated free algebra needs of its coefficients.
pub trait Scalar: Clone + fmt::Display {
    /// True when arithmetic is exact (zero tests are then exact).
    const EXACT: bool;
    fn zero() -> Self;
    /// `num / den`; `den` must not be 0.
    fn ratio(num: i64, den: i64) -> Self;
    fn plus(&self, rhs: &Self) -> Self;
    fn minus(&self, rhs: &Self) -> Self;
    fn times(&self, rhs: &Self) -> Self;
    fn negated(&self) -> Self;
    /// Exactly zero (also for `f64`: used to skip work, never to decide an order).
    fn is_zero(&self) -> bool;
    fn to_f64(&self) -> f64;

    /// Zero for the purpose of an order decision: exactly zero for exact fields, at most
    /// `FLOAT_TOLERANCE * scale` in magnitude for `f64` (NaN is never negligible).
    fn negligible(&self, scale: f64) -> bool {
        if Self::EXACT {
            self.is_zero()
        } else {
            self.to_f64().abs() <= FLOAT_TOLERANCE * scale
        }
    }
}

impl Scalar for f64 {
    const EXACT: bool = false;
    fn zero() -> Self {
        0.0
    }
    fn ratio(num: i64, den: i64) -> Self {
        num as f64 / den as f64
    }
    fn plus(&self, rhs: &Self) -> Self {
        self + rhs
    }
    fn minus(&self, rhs: &Self) -> Self {
        self - rhs
    }
    fn times(&self, rhs: &Self) -> Self {
        self * rhs
    }
    fn negated(&self) -> Self {
        -self
    }
    fn is_zero(&self) -> bool {
        *self == 0.0
    }
    fn to_f64(&self) -> f64 {
        *self
    }
}

/// An exact rational number: a reduced `i128` fraction (denominator > 0) while it fits, a
/// [`BigRational`] otherwise.
#[derive(Clone, Debug)]
pub enum Rational {
    Small(i128, i128),
    Big(BigRational),
}

impl Rational {
    /// Converts a `BigRational`; `None` for a zero denominator (a malformed `new_raw` value).
    pub fn from_big(value: &BigRational) -> Option<Rational> {
        if value.denom().is_zero() {
            return None;
        }
        Some(Self::demote(BigRational::new(
            value.numer().clone(),
            value.denom().clone(),
        )))
    }

    /// Small form of a normalised big value when it fits.
    fn demote(value: BigRational) -> Rational {
        match (value.numer().to_i128(), value.denom().to_i128()) {
            (Some(n), Some(d)) => Rational::Small(n, d),
            _ => Rational::Big(value),
        }
    }

    fn to_big(&self) -> BigRational {
        match self {
            Rational::Small(n, d) => BigRational::new_raw(BigInt::from(*n), BigInt::from(*d)),
            Rational::Big(b) => b.clone(),
        }
    }

    /// `n / d` reduced, for `d > 0`; `None` if the reduction cannot be represented.
    fn reduced(n: i128, d: i128) -> Option<Rational> {
        if n == 0 {
            return Some(Rational::Small(0, 1));
        }
        let g = gcd(n.unsigned_abs(), d.unsigned_abs());
        let g = i128::try_from(g).ok()?;
        Some(Rational::Small(n / g, d / g))
    }

    fn small_add(a: i128, b: i128, c: i128, d: i128) -> Option<Rational> {
        let g = i128::try_from(gcd(b.unsigned_abs(), d.unsigned_abs())).ok()?;
        let (b1, d1) = (b / g, d / g);
        let n = a.checked_mul(d1)?.checked_add(c.checked_mul(b1)?)?;
        Self::reduced(n, b.checked_mul(d1)?)
    }

    fn small_mul(a: i128, b: i128, c: i128, d: i128) -> Option<Rational> {
        if a == 0 || c == 0 {
            return Some(Rational::Small(0, 1));
        }
        let g1 = i128::try_from(gcd(a.unsigned_abs(), d.unsigned_abs())).ok()?;
        let g2 = i128::try_from(gcd(c.unsigned_abs(), b.unsigned_abs())).ok()?;
        let n = (a / g1).checked_mul(c / g2)?;
        let den = (b / g2).checked_mul(d / g1)?;
        Some(Rational::Small(n, den))
    }
}

/// Binary gcd; `gcd(0, x) = x`.
fn gcd(mut a: u128, mut b: u128) -> u128 {
    if a == 0 {
        return b;
    }
    if b == 0 {
        return a;
    }
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    loop {
        b >>= b.trailing_zeros();
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        b -= a;
        if b == 0 {
            return a << shift;
        }
    }
}

impl Scalar for Rational {
    const EXACT: bool = true;
    fn zero() -> Self {
        Rational::Small(0, 1)
    }
    fn ratio(num: i64, den: i64) -> Self {
        let (n, d) = (i128::from(num), i128::from(den));
        let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
        Self::reduced(n, d).unwrap_or(Rational::Small(0, 1))
    }
    fn plus(&self, rhs: &Self) -> Self {
        if let (Rational::Small(a, b), Rational::Small(c, d)) = (self, rhs) {
            if let Some(r) = Self::small_add(*a, *b, *c, *d) {
                return r;
            }
        }
        Self::demote(self.to_big() + rhs.to_big())
    }
    fn minus(&self, rhs: &Self) -> Self {
        self.plus(&rhs.negated())
    }
    fn times(&self, rhs: &Self) -> Self {
        if let (Rational::Small(a, b), Rational::Small(c, d)) = (self, rhs) {
            if let Some(r) = Self::small_mul(*a, *b, *c, *d) {
                return r;
            }
        }
        Self::demote(self.to_big() * rhs.to_big())
    }
    fn negated(&self) -> Self {
        match self {
            Rational::Small(n, d) => match n.checked_neg() {
                Some(m) => Rational::Small(m, *d),
                None => Self::demote(-self.to_big()),
            },
            Rational::Big(b) => Self::demote(-b),
        }
    }
    fn is_zero(&self) -> bool {
        match self {
            Rational::Small(n, _) => *n == 0,
            Rational::Big(b) => b.is_zero(),
        }
    }
    fn to_f64(&self) -> f64 {
        match self {
            Rational::Small(n, d) => *n as f64 / *d as f64,
            Rational::Big(b) => big_to_f64(b),
        }
    }
}

/// `f64` value of a big rational, also when numerator and denominator overflow `f64`.
fn big_to_f64(b: &BigRational) -> f64 {
    let (n, d) = (b.numer(), b.denom());
    let excess = n.bits().max(d.bits()).saturating_sub(1000);
    let (n, d) = (n >> excess, d >> excess);
    match (n.to_f64(), d.to_f64()) {
        (Some(n), Some(d)) if d != 0.0 => n / d,
        _ if b.is_negative() => f64::NEG_INFINITY,
        _ => f64::INFINITY,
    }
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Rational::Small(n, 1) => write!(f, "{n}"),
            Rational::Small(n, d) => write!(f, "{n}/{d}"),
            Rational::Big(b) => write!(f, "{b}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn big(n: i64, d: i64) -> BigRational {
        BigRational::new(n.into(), d.into())
    }

    proptest! {
        #[test]
        fn small_arithmetic_matches_big(a in -1000i64..1000, b in 1i64..1000,
                                        c in -1000i64..1000, d in 1i64..1000) {
            let (x, y) = (Rational::ratio(a, b), Rational::ratio(c, d));
            prop_assert_eq!(x.plus(&y).to_big(), big(a, b) + big(c, d));
            prop_assert_eq!(x.minus(&y).to_big(), big(a, b) - big(c, d));
            prop_assert_eq!(x.times(&y).to_big(), big(a, b) * big(c, d));
        }
    }

    #[test]
    fn overflow_falls_back_to_big_and_demotes_again() {
        let huge = Rational::Small(i128::MAX, 1);
        let sum = huge.plus(&huge);
        assert!(matches!(sum, Rational::Big(_)));
        let back = sum.minus(&huge);
        assert!(matches!(back, Rational::Small(n, 1) if n == i128::MAX));
        let min = Rational::Small(i128::MIN, 1);
        assert!(matches!(min.negated(), Rational::Big(_)));
        let sq = huge.times(&huge);
        assert!(sq.to_f64().is_finite());
        assert_eq!(sq.times(&Rational::zero()).to_string(), "0");
    }

    #[test]
    fn zero_denominator_is_rejected() {
        let bad = BigRational::new_raw(1.into(), 0.into());
        assert!(Rational::from_big(&bad).is_none());
    }
}
