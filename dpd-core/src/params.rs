//! Interaction parameters of the DPD pair forces (algorithms.md section 1), validated at
//! construction.

use crate::error::{non_negative, positive, ParamError};
use crate::potential::Soft;
use serde::{Deserialize, Serialize};

/// Validated pair-force parameters.
///
/// - `a[ti][tj]`: conservative repulsion between particle types (symmetric, finite, >= 0);
///   `F^C = a (1 - r/r_c) e`.
/// - `gamma`: dissipation strength (finite, >= 0).
/// - `kbt`: target temperature k_B T (finite, > 0).
/// - `sigma`: noise amplitude, derived from fluctuation-dissipation: `sigma^2 = 2 gamma kbt`.
/// - `rc`: cutoff radius (finite, > 0).
/// - `s`: weight exponent, `w_D = (1 - r/r_c)^s`, `w_R = (1 - r/r_c)^(s/2)` (finite, > 0).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "ParamsBuilder", into = "ParamsBuilder")]
pub struct Params {
    a: Vec<f64>,
    types: usize,
    gamma: f64,
    kbt: f64,
    sigma: f64,
    rc: f64,
    s: f64,
}

/// Unvalidated parameters; [`ParamsBuilder::build`] checks them. Defaults are the standard
/// equilibrium box of algorithms.md section 8 (a = 25, gamma = 4.5, k_B T = 1, r_c = 1, s = 2).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParamsBuilder {
    /// Repulsion matrix, one row per particle type.
    pub a: Vec<Vec<f64>>,
    pub gamma: f64,
    pub kbt: f64,
    pub rc: f64,
    /// Weight exponent `s`.
    pub weight_exponent: f64,
}

impl Default for ParamsBuilder {
    fn default() -> Self {
        ParamsBuilder {
            a: vec![vec![25.0]],
            gamma: 4.5,
            kbt: 1.0,
            rc: 1.0,
            weight_exponent: 2.0,
        }
    }
}

impl ParamsBuilder {
    /// One particle type with repulsion `a`.
    pub fn a(mut self, a: f64) -> Self {
        self.a = vec![vec![a]];
        self
    }
    pub fn a_matrix(mut self, a: Vec<Vec<f64>>) -> Self {
        self.a = a;
        self
    }
    pub fn gamma(mut self, gamma: f64) -> Self {
        self.gamma = gamma;
        self
    }
    pub fn kbt(mut self, kbt: f64) -> Self {
        self.kbt = kbt;
        self
    }
    pub fn rc(mut self, rc: f64) -> Self {
        self.rc = rc;
        self
    }
    pub fn weight_exponent(mut self, s: f64) -> Self {
        self.weight_exponent = s;
        self
    }

    /// Validate every field; the first invalid one is reported.
    pub fn build(self) -> Result<Params, ParamError> {
        let types = self.a.len();
        if types == 0 || types > u16::MAX as usize {
            return Err(ParamError::new(
                "a",
                format!("{types} rows"),
                "needs one row per particle type (1 to 65535 types)",
            ));
        }
        let mut a = Vec::with_capacity(types * types);
        for (i, row) in self.a.iter().enumerate() {
            if row.len() != types {
                return Err(ParamError::new(
                    format!("a[{i}]"),
                    format!("{} entries", row.len()),
                    format!("must have {types} entries (a square matrix)"),
                ));
            }
            for (j, &v) in row.iter().enumerate() {
                non_negative(&format!("a[{i}][{j}]"), v)?;
                if v != self.a[j][i] {
                    return Err(ParamError::new(
                        format!("a[{i}][{j}]"),
                        v,
                        format!("must equal a[{j}][{i}] = {} (a is symmetric)", self.a[j][i]),
                    ));
                }
                a.push(v);
            }
        }
        let gamma = non_negative("gamma", self.gamma)?;
        let kbt = positive("kbt", self.kbt)?;
        let rc = positive("rc", self.rc)?;
        let s = positive("weight_exponent", self.weight_exponent)?;
        let sigma = (2.0 * gamma * kbt).sqrt();
        if !sigma.is_finite() {
            return Err(ParamError::new(
                "gamma",
                gamma,
                format!("2 gamma kbt must be finite (kbt = {kbt})"),
            ));
        }
        Ok(Params {
            a,
            types,
            gamma,
            kbt,
            sigma,
            rc,
            s,
        })
    }
}

impl Params {
    /// Start from the standard-box defaults.
    pub fn builder() -> ParamsBuilder {
        ParamsBuilder::default()
    }

    /// Repulsion between types `ti` and `tj`.
    #[inline(always)]
    pub fn a(&self, ti: u16, tj: u16) -> f64 {
        self.repulsion().of(ti, tj)
    }

    /// The repulsion matrix, as a value a pair loop keeps in registers.
    #[inline(always)]
    pub fn repulsion(&self) -> Repulsion<'_> {
        Repulsion {
            a: &self.a,
            types: self.types,
            rc: self.rc,
        }
    }
    /// The soft repulsion between types `ti` and `tj` ([`crate::potential`]).
    #[inline(always)]
    pub fn soft(&self, ti: u16, tj: u16) -> Soft {
        Soft::new(self.a(ti, tj), self.rc)
    }
    pub fn types(&self) -> usize {
        self.types
    }
    pub fn gamma(&self) -> f64 {
        self.gamma
    }
    pub fn kbt(&self) -> f64 {
        self.kbt
    }
    /// `sqrt(2 gamma kbt)`.
    pub fn sigma(&self) -> f64 {
        self.sigma
    }
    pub fn rc(&self) -> f64 {
        self.rc
    }
    /// Weight exponent `s`.
    pub fn weight_exponent(&self) -> f64 {
        self.s
    }

    /// `w_R(r) = (1 - r/r_c)^(s/2)` for `r < r_c`, given `w = 1 - r/r_c`.
    #[inline(always)]
    pub fn w_r(&self, w: f64) -> f64 {
        if self.s == 2.0 {
            w
        } else if self.s == 1.0 {
            w.sqrt()
        } else {
            w.powf(0.5 * self.s)
        }
    }
}

/// The repulsion `a_ij` between particle types, with the cutoff ([`Params::repulsion`]).
#[derive(Clone, Copy, Debug)]
pub struct Repulsion<'a> {
    a: &'a [f64],
    types: usize,
    rc: f64,
}

impl Repulsion<'_> {
    /// Repulsion between types `ti` and `tj`.
    #[inline(always)]
    pub fn of(self, ti: u16, tj: u16) -> f64 {
        self.a[ti as usize * self.types + tj as usize]
    }

    /// The soft repulsion between two particles, `types` giving their types. With one type
    /// `types` is not called: a pair loop then loads two values fewer per pair.
    #[inline(always)]
    pub(crate) fn soft(self, types: impl FnOnce() -> (u16, u16)) -> Soft {
        let a = if self.types == 1 {
            self.a[0]
        } else {
            let (ti, tj) = types();
            self.of(ti, tj)
        };
        Soft::new(a, self.rc)
    }
}

impl TryFrom<ParamsBuilder> for Params {
    type Error = ParamError;
    fn try_from(b: ParamsBuilder) -> Result<Self, ParamError> {
        b.build()
    }
}

impl From<Params> for ParamsBuilder {
    fn from(p: Params) -> Self {
        ParamsBuilder {
            a: p.a.chunks(p.types).map(|r| r.to_vec()).collect(),
            gamma: p.gamma,
            kbt: p.kbt,
            rc: p.rc,
            weight_exponent: p.s,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_the_standard_box() {
        let p = Params::builder().build().unwrap();
        assert_eq!(p.a(0, 0), 25.0);
        assert_eq!(p.sigma(), 3.0);
    }

    #[test]
    fn each_field_is_named_when_invalid() {
        let cases: Vec<(ParamsBuilder, &str)> = vec![
            (Params::builder().gamma(-1.0), "gamma"),
            (Params::builder().gamma(f64::NAN), "gamma"),
            (Params::builder().kbt(0.0), "kbt"),
            (Params::builder().kbt(f64::INFINITY), "kbt"),
            (Params::builder().rc(-1.0), "rc"),
            (Params::builder().weight_exponent(0.0), "weight_exponent"),
            (Params::builder().a(f64::NAN), "a[0][0]"),
            (
                Params::builder().a_matrix(vec![vec![1.0, 2.0], vec![3.0, 1.0]]),
                "a[0][1]",
            ),
            (
                Params::builder().a_matrix(vec![vec![1.0, 2.0], vec![2.0]]),
                "a[1]",
            ),
            (Params::builder().a_matrix(vec![]), "a"),
            (Params::builder().gamma(1e308).kbt(1e308), "gamma"),
        ];
        for (b, field) in cases {
            let e = b.build().unwrap_err();
            assert_eq!(e.field, field, "{e}");
            assert!(e.to_string().contains(field));
        }
    }

    #[test]
    fn weights_follow_the_exponent() {
        let p = Params::builder().weight_exponent(0.5).build().unwrap();
        approx::assert_relative_eq!(p.w_r(0.25), 0.25f64.powf(0.25));
        let p = Params::builder().build().unwrap();
        assert_eq!(p.w_r(0.25), 0.25);
    }
}
