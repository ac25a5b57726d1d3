//! Interaction parameters of the DPD pair forces (algorithms.md section 1), validated at
//! construction.

mod pairs;

use crate::error::{non_negative, positive, ParamError};
use crate::potential::Soft;
use pairs::symmetric;
pub use pairs::Coefficients;
use serde::{Deserialize, Serialize};

/// Validated pair-force parameters.
///
/// - `a[ti][tj]`: conservative repulsion between particle types (symmetric, finite, >= 0);
///   `F^C = a (1 - r/r_c) e`.
/// - `gamma`: dissipation strength (finite, >= 0), one for every pair of types, or
///   `gamma_ij` per pair of types (`gamma_matrix`).
/// - `kbt`: target temperature k_B T (finite, > 0).
/// - `sigma`: noise amplitude, derived from fluctuation-dissipation: `sigma^2 = 2 gamma kbt`
///   (per pair of types, `sigma_ij^2 = 2 gamma_ij kbt`).
/// - `rc`: cutoff radius (finite, > 0), which sizes the neighbour cells; optionally
///   `r_c,ij <= rc` per pair of types (`rc_matrix`).
/// - `s`: weight exponent, `w_D = (1 - r/r_c)^s`, `w_R = (1 - r/r_c)^(s/2)` (finite, > 0).
/// - `collision_rate`: the Lowe-Andersen collision frequency Gamma of every pair within `rc`
///   (per unit time, finite, > 0), for schemes with an L stage; unset otherwise.
/// - `thermostat_mass`: the mass `mu` of PAdL's adaptive friction factor `xi` (an energy, in
///   the units of `kbt`; finite, > 0), for schemes with Oa and Xi: at equilibrium `xi` is
///   Gaussian around 1 with variance `kbt / mu` (PNHL, On and Xi: around 0). Unset otherwise.
/// - `thermostat_friction`: the friction `gamma_xi` of the Langevin dynamics of `xi` in the
///   pairwise Nose-Hoover-Langevin thermostat (PNHL; per unit time, finite, > 0), for schemes
///   with On and Xi; unset otherwise (and refused with Oa, whose `xi` centres on 1).
///
/// A matrix whose entries are all equal (for the cut-offs: all equal to `rc`) is stored as one
/// value, so that a system whose pairs share a coefficient runs the loops of one.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "ParamsBuilder", into = "ParamsBuilder")]
pub struct Params {
    a: Vec<f64>,
    types: usize,
    /// The largest `gamma_ij` and `sigma_ij` (every pair's when `gamma_ij` is empty).
    gamma: f64,
    sigma: f64,
    /// `gamma_ij` and `sigma_ij` row-major when they differ between pairs; else empty.
    gamma_ij: Vec<f64>,
    sigma_ij: Vec<f64>,
    kbt: f64,
    rc: f64,
    /// `r_c,ij` row-major when some differs from `rc`; else empty.
    rc_ij: Vec<f64>,
    s: f64,
    collision_rate: Option<f64>,
    thermostat_mass: Option<f64>,
    thermostat_friction: Option<f64>,
}

/// Unvalidated parameters; [`ParamsBuilder::build`] checks them. Defaults are the standard
/// equilibrium box of algorithms.md section 8 (a = 25, gamma = 4.5, k_B T = 1, r_c = 1, s = 2).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParamsBuilder {
    /// Repulsion matrix, one row per particle type.
    pub a: Vec<Vec<f64>>,
    /// The friction of every pair of types, unless `gamma_matrix` is given.
    pub gamma: f64,
    /// Friction `gamma_ij` per pair of types (symmetric, finite, >= 0, one row per type); when
    /// given, `gamma` is not used.
    #[serde(default)]
    pub gamma_matrix: Option<Vec<Vec<f64>>>,
    pub kbt: f64,
    /// The cut-off of every pair, or the largest one (which sizes the neighbour cells) when
    /// `rc_matrix` is given.
    pub rc: f64,
    /// Cut-off `r_c,ij` per pair of types (symmetric, in `(0, rc]`, one row per type).
    #[serde(default)]
    pub rc_matrix: Option<Vec<Vec<f64>>>,
    /// Weight exponent `s`.
    pub weight_exponent: f64,
    /// Lowe-Andersen collision frequency Gamma (per unit time), for schemes with L. Not in
    /// the serialised form, whose layout checkpoints of version 7 and 8 fixed: checkpoints
    /// store it after the topology (`crate::checkpoint`).
    #[serde(skip)]
    pub collision_rate: Option<f64>,
    /// The mass `mu` of PAdL's friction factor (energy units), for schemes with Oa and Xi;
    /// stored by checkpoints after the collision rate, as that is.
    #[serde(skip)]
    pub thermostat_mass: Option<f64>,
    /// The friction `gamma_xi` of PNHL's `xi` (per unit time), for schemes with On and Xi;
    /// stored by checkpoints after the thermostat mass.
    #[serde(skip)]
    pub thermostat_friction: Option<f64>,
}

impl Default for ParamsBuilder {
    fn default() -> Self {
        ParamsBuilder {
            a: vec![vec![25.0]],
            gamma: 4.5,
            gamma_matrix: None,
            kbt: 1.0,
            rc: 1.0,
            rc_matrix: None,
            weight_exponent: 2.0,
            collision_rate: None,
            thermostat_mass: None,
            thermostat_friction: None,
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
    /// Friction per pair of types (replaces `gamma`).
    pub fn gamma_matrix(mut self, gamma: Vec<Vec<f64>>) -> Self {
        self.gamma_matrix = Some(gamma);
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
    /// Cut-off per pair of types, each at most `rc`.
    pub fn rc_matrix(mut self, rc: Vec<Vec<f64>>) -> Self {
        self.rc_matrix = Some(rc);
        self
    }
    pub fn weight_exponent(mut self, s: f64) -> Self {
        self.weight_exponent = s;
        self
    }
    /// Lowe-Andersen collision frequency Gamma, per unit time.
    pub fn collision_rate(mut self, rate: f64) -> Self {
        self.collision_rate = Some(rate);
        self
    }
    /// The mass `mu` of PAdL's adaptive friction factor, in energy units.
    pub fn thermostat_mass(mut self, mu: f64) -> Self {
        self.thermostat_mass = Some(mu);
        self
    }
    /// The friction `gamma_xi` of PNHL's friction factor, per unit time.
    pub fn thermostat_friction(mut self, gamma_xi: f64) -> Self {
        self.thermostat_friction = Some(gamma_xi);
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
        let at_least_zero = |v: f64| match v >= 0.0 {
            true => Ok(()),
            false => Err(String::from("must be finite and >= 0")),
        };
        let a = symmetric("a", &self.a, types, at_least_zero)?;
        let gamma = non_negative("gamma", self.gamma)?;
        let kbt = positive("kbt", self.kbt)?;
        let rc = positive("rc", self.rc)?;
        let s = positive("weight_exponent", self.weight_exponent)?;
        let collision_rate = (self.collision_rate)
            .map(|g| positive("collision_rate", g))
            .transpose()?;
        let thermostat_mass = (self.thermostat_mass)
            .map(|mu| positive("thermostat_mass", mu))
            .transpose()?;
        let thermostat_friction = (self.thermostat_friction)
            .map(|g| positive("thermostat_friction", g))
            .transpose()?;
        let gamma_ij = match &self.gamma_matrix {
            Some(rows) => symmetric("gamma_matrix", rows, types, at_least_zero)?,
            None => vec![gamma],
        };
        let field = |k: usize| match self.gamma_matrix {
            Some(_) => format!("gamma_matrix[{}][{}]", k / types, k % types),
            None => String::from("gamma"),
        };
        let sigma_ij = (gamma_ij.iter().enumerate())
            .map(|(k, &g)| noise_amplitude(&field(k), g, kbt))
            .collect::<Result<Vec<f64>, _>>()?;
        let within = |v: f64| match v > 0.0 && v <= rc {
            true => Ok(()),
            false => Err(format!(
                "must be > 0 and at most rc = {rc} (the largest cut-off)"
            )),
        };
        let rc_ij = match &self.rc_matrix {
            Some(rows) => symmetric("rc_matrix", rows, types, within)?,
            None => vec![rc],
        };
        let largest = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
        let (gamma, sigma) = (largest(&gamma_ij), largest(&sigma_ij));
        let differ = |v: Vec<f64>, one: f64| {
            if v.iter().all(|&x| x == one) {
                Vec::new()
            } else {
                v
            }
        };
        let (gamma_ij, sigma_ij) = match differ(gamma_ij, gamma) {
            g if g.is_empty() => (g, Vec::new()),
            g => (g, sigma_ij),
        };
        Ok(Params {
            a,
            types,
            gamma,
            sigma,
            gamma_ij,
            sigma_ij,
            kbt,
            rc,
            rc_ij: differ(rc_ij, rc),
            s,
            collision_rate,
            thermostat_mass,
            thermostat_friction,
        })
    }
}

/// `sigma = sqrt(2 gamma kbt)`, an error naming `field` unless it is finite.
fn noise_amplitude(field: &str, gamma: f64, kbt: f64) -> Result<f64, ParamError> {
    let sigma = (2.0 * gamma * kbt).sqrt();
    if sigma.is_finite() {
        Ok(sigma)
    } else {
        Err(ParamError::new(
            field,
            gamma,
            format!("2 gamma kbt must be finite (kbt = {kbt})"),
        ))
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
        self.coefficients().a(ti, tj)
    }

    /// The coefficients of every pair of types, as a value a pair loop keeps in registers.
    #[inline(always)]
    pub fn coefficients(&self) -> Coefficients<'_> {
        Coefficients {
            a: &self.a,
            types: self.types,
            rc: self.rc,
            uniform: (self.gamma, self.sigma),
            gamma: &self.gamma_ij,
            sigma: &self.sigma_ij,
            cutoff: &self.rc_ij,
        }
    }
    /// The soft repulsion between types `ti` and `tj`, with their cut-off
    /// ([`crate::potential`]).
    #[inline(always)]
    pub fn soft(&self, ti: u16, tj: u16) -> Soft {
        self.coefficients().soft(|| (ti, tj))
    }
    pub fn types(&self) -> usize {
        self.types
    }
    /// The largest friction `gamma_ij` (every pair's, unless they differ:
    /// [`Params::friction_by_type`]).
    pub fn gamma(&self) -> f64 {
        self.gamma
    }
    /// The friction `gamma_ij` and noise amplitude `sigma_ij` between types `ti` and `tj`.
    pub fn friction(&self, ti: u16, tj: u16) -> (f64, f64) {
        self.coefficients().friction(|| (ti, tj))
    }
    /// Whether the frictions of the pairs of types differ.
    pub fn friction_by_type(&self) -> bool {
        !self.gamma_ij.is_empty()
    }
    pub fn kbt(&self) -> f64 {
        self.kbt
    }
    /// The largest `sigma_ij = sqrt(2 gamma_ij kbt)`.
    pub fn sigma(&self) -> f64 {
        self.sigma
    }
    /// The largest cut-off, which sizes the neighbour cells (every pair's, unless they differ:
    /// [`Params::cutoff_by_type`]).
    pub fn rc(&self) -> f64 {
        self.rc
    }
    /// The cut-off `r_c,ij` between types `ti` and `tj`.
    pub fn rc_of(&self, ti: u16, tj: u16) -> f64 {
        self.coefficients().rc(|| (ti, tj))
    }
    /// Whether the cut-offs of the pairs of types differ from [`Params::rc`].
    pub fn cutoff_by_type(&self) -> bool {
        !self.rc_ij.is_empty()
    }
    /// Weight exponent `s`.
    pub fn weight_exponent(&self) -> f64 {
        self.s
    }
    /// The Lowe-Andersen collision frequency Gamma (per unit time), if set.
    pub fn collision_rate(&self) -> Option<f64> {
        self.collision_rate
    }
    /// The mass `mu` of PAdL's adaptive friction factor (energy units), if set.
    pub fn thermostat_mass(&self) -> Option<f64> {
        self.thermostat_mass
    }
    /// The friction `gamma_xi` of PNHL's friction factor (per unit time), if set.
    pub fn thermostat_friction(&self) -> Option<f64> {
        self.thermostat_friction
    }

    /// `w_R(r) = (1 - r/r_c)^(s/2)` for `r < r_c`, given `w = 1 - r/r_c`.
    #[inline(always)]
    pub fn w_r(&self, w: f64) -> f64 {
        self.random_weight()(w)
    }

    /// [`Params::w_r`] as a function holding the exponent by value: a pair loop that stores
    /// through pointers keeps it in a register, where `w_r` read it from `self` for every pair.
    #[inline(always)]
    pub fn random_weight(&self) -> impl Fn(f64) -> f64 + Copy + Sync {
        let s = self.s;
        move |w: f64| {
            if s == 2.0 {
                w
            } else if s == 1.0 {
                w.sqrt()
            } else {
                w.powf(0.5 * s)
            }
        }
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
        let rows = |v: &[f64]| v.chunks(p.types).map(|r| r.to_vec()).collect::<Vec<_>>();
        let matrix = |v: &[f64]| (!v.is_empty()).then(|| rows(v));
        ParamsBuilder {
            a: rows(&p.a),
            gamma: p.gamma,
            gamma_matrix: matrix(&p.gamma_ij),
            kbt: p.kbt,
            rc: p.rc,
            rc_matrix: matrix(&p.rc_ij),
            weight_exponent: p.s,
            collision_rate: p.collision_rate,
            thermostat_mass: p.thermostat_mass,
            thermostat_friction: p.thermostat_friction,
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
            (Params::builder().collision_rate(0.0), "collision_rate"),
            (Params::builder().collision_rate(f64::NAN), "collision_rate"),
            (Params::builder().thermostat_mass(-1.0), "thermostat_mass"),
            (Params::builder().thermostat_mass(0.0), "thermostat_mass"),
            (
                Params::builder().thermostat_mass(f64::NAN),
                "thermostat_mass",
            ),
            (
                Params::builder().thermostat_friction(-1.0),
                "thermostat_friction",
            ),
            (
                Params::builder().thermostat_friction(f64::NAN),
                "thermostat_friction",
            ),
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
            (
                two().gamma_matrix(vec![vec![1.0, 2.0], vec![3.0, 1.0]]),
                "gamma_matrix[0][1]",
            ),
            (two().gamma_matrix(vec![vec![1.0, 2.0]]), "gamma_matrix"),
            (
                two().gamma_matrix(vec![vec![1.0], vec![1.0]]),
                "gamma_matrix[0]",
            ),
            (
                two().gamma_matrix(vec![vec![-1.0, 0.0], vec![0.0, 1.0]]),
                "gamma_matrix[0][0]",
            ),
            (
                two()
                    .gamma_matrix(vec![vec![1.0, 1e308], vec![1e308, 1.0]])
                    .kbt(10.0),
                "gamma_matrix[0][1]",
            ),
            (
                two().rc_matrix(vec![vec![1.0, 1.5], vec![1.5, 1.0]]),
                "rc_matrix[0][1]",
            ),
            (
                two().rc_matrix(vec![vec![1.0, 0.0], vec![0.0, 1.0]]),
                "rc_matrix[0][1]",
            ),
            (
                two().rc_matrix(vec![vec![f64::NAN, 1.0], vec![1.0, 1.0]]),
                "rc_matrix[0][0]",
            ),
        ];
        for (b, field) in cases {
            let e = b.build().unwrap_err();
            assert_eq!(e.field, field, "{e}");
            assert!(e.to_string().contains(field));
        }
    }

    /// Two types, a = 25.
    fn two() -> ParamsBuilder {
        Params::builder().a_matrix(vec![vec![25.0; 2]; 2])
    }

    /// Friction and cut-off per pair of types are read per pair, the largest is what `gamma`,
    /// `sigma` and `rc` report, and a matrix of one value is stored as that value.
    #[test]
    fn pairs_of_types_have_their_own_friction_and_cutoff() {
        let p = two()
            .gamma_matrix(vec![vec![2.0, 8.0], vec![8.0, 0.5]])
            .rc(1.2)
            .rc_matrix(vec![vec![1.0, 1.2], vec![1.2, 0.7]])
            .kbt(2.0)
            .build()
            .unwrap();
        assert_eq!(p.friction(0, 1), (8.0, 32f64.sqrt()));
        assert_eq!(p.friction(1, 1), (0.5, 2f64.sqrt()));
        assert_eq!((p.gamma(), p.sigma(), p.rc()), (8.0, 32f64.sqrt(), 1.2));
        assert_eq!(
            (p.rc_of(0, 0), p.rc_of(1, 0), p.rc_of(1, 1)),
            (1.0, 1.2, 0.7)
        );
        assert_eq!(p.soft(1, 1), Soft::new(25.0, 0.7));
        assert!(p.friction_by_type() && p.cutoff_by_type());
        let back: ParamsBuilder = p.clone().into();
        assert_eq!(back.build(), Ok(p));
        let one = two()
            .gamma_matrix(vec![vec![3.0; 2]; 2])
            .rc_matrix(vec![vec![1.0; 2]; 2])
            .build()
            .unwrap();
        assert_eq!(one, two().gamma(3.0).build().unwrap());
        assert!(!one.friction_by_type() && !one.cutoff_by_type());
    }

    #[test]
    fn weights_follow_the_exponent() {
        let p = Params::builder().weight_exponent(0.5).build().unwrap();
        approx::assert_relative_eq!(p.w_r(0.25), 0.25f64.powf(0.25));
        let p = Params::builder().build().unwrap();
        assert_eq!(p.w_r(0.25), 0.25);
    }
}
