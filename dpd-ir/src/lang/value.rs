//! Numbers of coefficient expressions: exact rationals while possible, `f64` otherwise.
//!
//! Every `f64` result is computed by the same sequence of IEEE operations on every platform:
//! exact rationals are rounded once (correctly, by `num-rational`), `+ - * /` are IEEE
//! operations, integer powers are binary exponentiation, and roots are computed with big
//! integers and rounded once. No platform `libm` function (`powf`, `cbrt`) is used, so a value
//! compiled into code by the macro equals the value computed at run time bit for bit.

use crate::program::Coeff;
use num_bigint::{BigInt, Sign};
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// Significant digits from which a number literal is a typed approximation of a real number
/// (read as the nearest `f64`) rather than an exact decimal: 13, so that coefficients copied
/// from a paper to 13-21 digits mean the number they approximate, while `0.1`, `5e-9` or
/// `0.123456789` mean exactly what they say.
pub const APPROXIMATE_DIGITS: usize = 13;

/// Largest numerator or denominator of an exact value, in bits.
pub const MAX_BITS: u64 = 4096;
/// Largest root index `q` of a power `x^(p/q)`.
pub const MAX_ROOT: u32 = 32;

/// A value of a coefficient expression.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Exact(BigRational),
    /// An irrational (or rounded) value; always finite.
    Float(f64),
}

type VResult = Result<Value, String>;

impl Value {
    pub fn int(n: i64) -> Value {
        Value::Exact(BigRational::from_integer(n.into()))
    }

    /// Parses a number literal (`12`, `0.25`, `1.5e-3`): exactly when it has fewer than
    /// [`APPROXIMATE_DIGITS`] significant digits, else as the nearest `f64` (a typed
    /// approximation of a real number, see the module docs of `lang`).
    pub fn parse(literal: &str) -> VResult {
        let (mantissa, exponent) = match literal.find(['e', 'E']) {
            Some(i) => (&literal[..i], &literal[i + 1..]),
            None => (literal, "0"),
        };
        let exponent: i64 = exponent
            .parse()
            .ok()
            .filter(|e: &i64| e.abs() <= 1000)
            .ok_or_else(|| format!("exponent of {literal} is too large"))?;
        let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
        let digits = format!("{int}{frac}");
        let n: BigInt = if digits.is_empty() {
            BigInt::zero()
        } else {
            digits
                .parse()
                .map_err(|_| format!("malformed number {literal}"))?
        };
        let scale = exponent - frac.len() as i64;
        let ten = BigInt::from(10);
        let p = ten.pow(scale.unsigned_abs() as u32);
        let significant = digits.trim_matches('0').len();
        let r = if scale >= 0 {
            BigRational::from_integer(n * p)
        } else {
            BigRational::new(n, p)
        };
        if significant >= APPROXIMATE_DIGITS {
            return float(r.to_f64().unwrap_or(f64::NAN))
                .map_err(|_| format!("{literal} is too large for an f64"));
        }
        exact(r)
    }

    /// The value as used at run time.
    pub fn to_f64(&self) -> f64 {
        match self {
            Value::Exact(r) => r.to_f64().unwrap_or(f64::NAN),
            Value::Float(x) => *x,
        }
    }

    pub fn is_zero(&self) -> bool {
        match self {
            Value::Exact(r) => r.is_zero(),
            Value::Float(x) => *x == 0.0,
        }
    }

    /// Whether the value is positive (decided exactly for exact values).
    pub fn is_positive(&self) -> bool {
        match self {
            Value::Exact(r) => r.is_positive(),
            Value::Float(x) => *x > 0.0,
        }
    }

    /// The coefficient of a stage; fails if the value does not fit an `f64`.
    pub fn to_coeff(&self) -> Result<Coeff, String> {
        let value = self.to_f64();
        if !value.is_finite() {
            return Err(format!("coefficient {self} is too large for an f64"));
        }
        Ok(Coeff {
            value,
            exact: match self {
                Value::Exact(r) => Some(r.clone()),
                Value::Float(_) => None,
            },
        })
    }

    pub fn neg(&self) -> Value {
        match self {
            Value::Exact(r) => Value::Exact(-r),
            Value::Float(x) => Value::Float(-x),
        }
    }

    pub fn add(&self, rhs: &Value) -> VResult {
        self.binary(rhs, |a, b| Ok(a + b), |a, b| a + b)
    }

    pub fn sub(&self, rhs: &Value) -> VResult {
        self.binary(rhs, |a, b| Ok(a - b), |a, b| a - b)
    }

    pub fn mul(&self, rhs: &Value) -> VResult {
        self.binary(rhs, |a, b| Ok(a * b), |a, b| a * b)
    }

    pub fn div(&self, rhs: &Value) -> VResult {
        if rhs.is_zero() {
            return Err("division by zero".to_string());
        }
        self.binary(rhs, |a, b| Ok(a / b), |a, b| a / b)
    }

    fn binary(
        &self,
        rhs: &Value,
        exact_op: impl FnOnce(&BigRational, &BigRational) -> Result<BigRational, String>,
        float_op: impl FnOnce(f64, f64) -> f64,
    ) -> VResult {
        match (self, rhs) {
            (Value::Exact(a), Value::Exact(b)) => exact(exact_op(a, b)?),
            _ => float(float_op(self.to_f64(), rhs.to_f64())),
        }
    }

    /// `self^exp`; the exponent must be rational, `p/q` with `q <= MAX_ROOT`.
    pub fn pow(&self, exp: &Value) -> VResult {
        let Value::Exact(e) = exp else {
            return Err(format!(
                "exponent {exp} is irrational; only rational exponents are supported"
            ));
        };
        let q = e
            .denom()
            .to_u32()
            .filter(|&q| q <= MAX_ROOT)
            .ok_or_else(|| format!("exponent {exp} has a denominator above {MAX_ROOT}"))?;
        let p = e
            .numer()
            .to_i64()
            .ok_or_else(|| format!("exponent {exp} is too large"))?;
        match self {
            Value::Exact(b) => {
                if b.is_zero() {
                    return match p {
                        p if p < 0 => Err("division by zero (0 to a negative power)".to_string()),
                        0 => Ok(Value::int(1)),
                        _ => Ok(Value::int(0)),
                    };
                }
                // b^p has at least (bits - 1) |p| + 1 bits: refuse before computing.
                let bits = b.numer().bits().max(b.denom().bits());
                let unit = b.abs().is_one();
                if !unit
                    && u128::from(bits - 1) * u128::from(p.unsigned_abs()) >= u128::from(MAX_BITS)
                {
                    return Err(format!(
                        "power too large: {self}^{p} needs more than {MAX_BITS} bits"
                    ));
                }
                // A unit base only needs the parity of p; otherwise |p| < MAX_BITS here.
                let expon = i32::try_from(if unit { p.rem_euclid(2) } else { p })
                    .map_err(|_| format!("exponent {exp} is too large"))?;
                root(&checked(b.pow(expon))?, q)
            }
            Value::Float(x) => {
                let r = if q == 1 {
                    *x
                } else {
                    let exact_x = BigRational::from_float(*x)
                        .ok_or_else(|| "coefficient is not finite".to_string())?;
                    root(&exact_x, q)?.to_f64()
                };
                float(powi(r, p))
            }
        }
    }

    /// The `q`-th root (`q = 2`: `sqrt`, `q = 3`: `cbrt`); exact for perfect powers.
    pub fn root(&self, q: u32) -> VResult {
        match self {
            Value::Exact(r) => root(r, q),
            Value::Float(x) => {
                let r = BigRational::from_float(*x)
                    .ok_or_else(|| "coefficient is not finite".to_string())?;
                Ok(Value::Float(root(&r, q)?.to_f64()))
            }
        }
    }
}

impl std::fmt::Display for Value {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Value::Exact(r) => f.write_str(&compact(r)),
            Value::Float(x) => write!(f, "{x:?}"),
        }
    }
}

/// Longest fraction, in characters, that messages print in full.
const LONGEST_SHOWN: usize = 40;

/// `r` as a fraction (`-3/8`) when that is short, else in scientific notation with 17
/// significant digits, after `~` when rounded (`1e309`, `~3.3333333333333333e-401`).
pub fn compact(r: &BigRational) -> String {
    let full = r.to_string();
    if full.len() <= LONGEST_SHOWN || r.is_zero() {
        return full;
    }
    let (n, d) = (r.numer().magnitude(), r.denom().magnitude());
    // Scale by 10^k so that the integer quotient has at least 17 digits.
    let digits = |x: &num_bigint::BigUint| x.to_string().len() as i64;
    let k = 17 - (digits(n) - digits(d));
    let ten = num_bigint::BigUint::from(10u32);
    let (num, den) = if k >= 0 {
        (n * ten.pow(k as u32), d.clone())
    } else {
        (n.clone(), d * ten.pow((-k) as u32))
    };
    let q = &num / &den;
    let q_digits = q.to_string();
    let exponent = q_digits.len() as i64 - 1 - k;
    let rounded = !(&num % &den).is_zero()
        || q_digits
            .get(17..)
            .is_some_and(|t| !t.trim_matches('0').is_empty());
    let mantissa = q_digits[..17.min(q_digits.len())].trim_end_matches('0');
    let mantissa = match mantissa.split_at(1) {
        (lead, "") => lead.to_string(),
        (lead, rest) => format!("{lead}.{rest}"),
    };
    let tilde = if rounded { "~" } else { "" };
    let sign = if r.is_negative() { "-" } else { "" };
    format!("{tilde}{sign}{mantissa}e{exponent}")
}

/// Checks the size of an exact result.
fn checked(r: BigRational) -> Result<BigRational, String> {
    if r.numer().bits() > MAX_BITS || r.denom().bits() > MAX_BITS {
        return Err(format!(
            "exact value needs more than {MAX_BITS} bits; use smaller numbers"
        ));
    }
    Ok(r)
}

fn exact(r: BigRational) -> VResult {
    checked(r).map(Value::Exact)
}

/// Checks that a float result is finite.
fn float(x: f64) -> VResult {
    if x.is_finite() {
        Ok(Value::Float(x))
    } else {
        Err("value is not finite (overflow or division by zero)".to_string())
    }
}

/// `x^p` by binary exponentiation (a fixed sequence of IEEE multiplications).
fn powi(x: f64, p: i64) -> f64 {
    let (mut base, mut n, mut acc) = (x, p.unsigned_abs(), 1.0);
    while n > 0 {
        if n & 1 == 1 {
            acc *= base;
        }
        base *= base;
        n >>= 1;
    }
    if p < 0 {
        1.0 / acc
    } else {
        acc
    }
}

/// The real `q`-th root of `r`: exact if `r` is a perfect `q`-th power, else rounded once
/// from a big-integer root with at least 64 significant bits.
fn root(r: &BigRational, q: u32) -> VResult {
    if q == 1 || r.is_zero() {
        return exact(r.clone());
    }
    if r.is_negative() {
        if q & 1 == 0 {
            return Err(format!("even root of the negative number {}", compact(r)));
        }
        return root(&-r, q).map(|v| v.neg());
    }
    let (a, b) = (r.numer().magnitude(), r.denom().magnitude());
    let (ra, rb) = (a.nth_root(q), b.nth_root(q));
    if ra.pow(q) == *a && rb.pow(q) == *b {
        return exact(BigRational::new(
            BigInt::from_biguint(Sign::Plus, ra),
            BigInt::from_biguint(Sign::Plus, rb),
        ));
    }
    // root(a/b) = root(a b^(q-1)) / b, scaled by 2^extra to keep 64 bits below the point.
    let n = a * b.pow(q - 1);
    let extra = 66u64.saturating_sub(n.bits() / u64::from(q));
    let scaled = (n << (extra * u64::from(q))).nth_root(q);
    let denom = b << extra;
    let value = BigRational::new(
        BigInt::from_biguint(Sign::Plus, scaled),
        BigInt::from_biguint(Sign::Plus, denom),
    );
    float(value.to_f64().unwrap_or(f64::NAN))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(s: &str) -> Value {
        Value::parse(s).unwrap()
    }

    #[test]
    fn literals_are_exact() {
        assert_eq!(
            v("0.25"),
            Value::Exact(BigRational::new(1.into(), 4.into()))
        );
        assert_eq!(v("1.5e-3").to_f64(), 0.0015);
        assert_eq!(v("2e3"), Value::int(2000));
        assert!(Value::parse("1e99999").is_err());
    }

    #[test]
    fn long_literals_are_approximations() {
        assert_eq!(
            v("0.123456789012"),
            Value::Exact(BigRational::new(
                123456789012i64.into(),
                1000000000000i64.into()
            ))
        );
        assert_eq!(v("0.1234567890123"), Value::Float(0.1234567890123));
        assert_eq!(
            v("-1.17767998417887100695"),
            Value::Float(-1.177_679_984_178_871)
        );
        assert_eq!(
            v("0.000000000000000000001"),
            Value::Exact(BigRational::new(1.into(), BigInt::from(10).pow(21)))
        );
        assert_eq!(v("1234567890123e290"), Value::Float(1.234567890123e302));
        assert!(Value::parse("1234567890123e300").is_err());
    }

    #[test]
    fn huge_and_tiny_values_print_compactly() {
        assert_eq!(v("1e309").to_string(), "1e309");
        assert_eq!(v("-2.5e-320").to_string(), "-2.5e-320");
        assert_eq!(
            v("1e300").div(&v("3")).unwrap().to_string(),
            "~3.3333333333333333e299"
        );
        assert_eq!(
            v("123456789").div(&v("1000")).unwrap().to_string(),
            "123456789/1000"
        );
        let e = v("1e309").to_coeff().unwrap_err();
        assert_eq!(e, "coefficient 1e309 is too large for an f64");
    }

    #[test]
    fn roots_of_perfect_powers_stay_exact() {
        let r = Value::Exact(BigRational::new(9.into(), 4.into()));
        assert_eq!(
            r.root(2).unwrap(),
            Value::Exact(BigRational::new(3.into(), 2.into()))
        );
        assert_eq!(Value::int(-8).root(3).unwrap(), Value::int(-2));
        assert!(Value::int(-8).root(2).is_err());
    }

    #[test]
    fn irrational_roots_are_correctly_rounded() {
        assert_eq!(Value::int(2).root(2).unwrap(), Value::Float(2f64.sqrt()));
        assert_eq!(
            Value::Float(2.0).root(2).unwrap(),
            Value::Float(2f64.sqrt())
        );
        let c = Value::int(2).root(3).unwrap().to_f64();
        assert!((c - 2f64.cbrt()).abs() <= f64::EPSILON);
    }

    #[test]
    fn powers() {
        let third = Value::Exact(BigRational::new(1.into(), 3.into()));
        let c = Value::int(2).pow(&third).unwrap();
        assert_eq!(c, Value::int(2).root(3).unwrap());
        assert_eq!(Value::int(2).pow(&Value::int(-2)).unwrap(), v("0.25"));
        assert_eq!(Value::int(-1).pow(&v("1e18")).unwrap(), Value::int(1));
        assert!(Value::int(10).pow(&v("1e10")).is_err());
        assert!(Value::int(3).pow(&Value::int(2580)).is_ok());
        assert!(Value::int(3).pow(&Value::int(2585)).is_err());
        assert!(Value::int(0).pow(&Value::int(-1)).is_err());
        assert!(Value::int(2).pow(&Value::Float(0.5)).is_err());
        assert!(Value::Float(1e300).pow(&Value::int(2)).is_err());
    }
}
