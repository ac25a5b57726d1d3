//! The `[sweep]` table: schemes over a geometric grid of time steps (algorithms.md section 7).

use super::check::{positive, require, steps_in_range};
use dpd_core::ParamError;
use serde::{Deserialize, Serialize};

/// A sweep of schemes over a geometric grid of time steps.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SweepSpec {
    pub schemes: Vec<String>,
    pub dt_min: f64,
    pub dt_max: f64,
    /// Ratio of neighbouring grid points; dt_k = dt_min dt_factor^k <= dt_max.
    pub dt_factor: f64,
    /// Efficiencies are scaled so that this scheme's is 1 (default: see
    /// [`SweepSpec::reference`]).
    pub reference: Option<String>,
    /// Scheme of the small-dt run that the potential energy and pressure are compared with.
    pub baseline_scheme: String,
    /// Time step of that run (default: dt_min).
    pub baseline_dt: Option<f64>,
    /// Whose relative error decides the critical step sizes.
    pub observable: Observable,
}

/// The accuracy measure of a sweep (algorithms.md sections 6 and 7).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Observable {
    /// (T_C - k_B T) / k_B T.
    #[default]
    ConfigurationalTemperature,
    /// The shear viscosity relative to the baseline run's (needs a non-zero `shear_rate`).
    Viscosity,
}

impl Observable {
    /// Every observable, in the order of their names in messages and help texts.
    pub const ALL: [Observable; 2] = [
        Observable::ConfigurationalTemperature,
        Observable::Viscosity,
    ];

    /// The name used in scenes, flags and JSON.
    pub fn name(self) -> &'static str {
        match self {
            Observable::ConfigurationalTemperature => "configurational-temperature",
            Observable::Viscosity => "viscosity",
        }
    }
}

impl Default for SweepSpec {
    fn default() -> Self {
        SweepSpec {
            schemes: vec!["vv".into(), "dpd-s1".into(), "aboba".into()],
            dt_min: 0.01,
            dt_max: 0.2,
            dt_factor: 1.15,
            reference: None,
            baseline_scheme: "aboba".into(),
            baseline_dt: None,
            observable: Observable::default(),
        }
    }
}

/// The reference scheme when the table names none: velocity Verlet where it is swept.
const DEFAULT_REFERENCE: &str = "vv";

impl SweepSpec {
    /// Check the table for runs of `time` in a scene that is `sheared` (non-zero shear rate)
    /// and has `walls` or not.
    pub fn validate(&self, time: f64, sheared: bool, walls: bool) -> Result<(), ParamError> {
        require(
            "sweep.schemes",
            format!("{:?}", self.schemes),
            !self.schemes.is_empty(),
            "must name at least one scheme",
        )?;
        positive("sweep.dt_min", self.dt_min)?;
        require(
            "sweep.dt_max",
            self.dt_max,
            self.dt_max.is_finite() && self.dt_max >= self.dt_min,
            &format!("must be finite and >= sweep.dt_min = {}", self.dt_min),
        )?;
        let f = self.dt_factor;
        require(
            "sweep.dt_factor",
            f,
            f.is_finite() && f > 1.0,
            "must be finite and > 1",
        )?;
        let points = (self.dt_max / self.dt_min).ln() / f.ln();
        require(
            "sweep.dt_factor",
            f,
            points < 1000.0,
            "gives more than 1000 grid points",
        )?;
        require(
            "sweep.reference",
            self.reference(),
            self.schemes.iter().any(|s| s == self.reference()),
            &format!("must be one of sweep.schemes {:?}", self.schemes),
        )?;
        if let Some(dt) = self.baseline_dt {
            positive("sweep.baseline_dt", dt)?;
        }
        steps_in_range(time, "sweep.dt_min", self.dt_min)?;
        steps_in_range(time, "sweep.dt_max", self.dt_max)?;
        steps_in_range(time, "sweep.baseline_dt", self.baseline_dt())?;
        require(
            "sweep.observable",
            self.observable.name(),
            self.observable != Observable::Viscosity || sheared,
            "needs a non-zero shear_rate (`shear_rate` in the scene or --shear-rate); \
             valid without it: configurational-temperature",
        )?;
        require(
            "sweep.observable",
            self.observable.name(),
            !walls,
            "is not measured between walls (T_C is null there and viscosity needs shear, \
             which walls exclude): sweep a scene without [walls]",
        )
    }

    /// The scheme whose efficiency is 1: `reference` if given, else `vv` where it is among
    /// the schemes, else the first scheme.
    pub fn reference(&self) -> &str {
        match &self.reference {
            Some(r) => r,
            None if self.schemes.iter().any(|s| s == DEFAULT_REFERENCE) => DEFAULT_REFERENCE,
            None => self
                .schemes
                .first()
                .map_or(DEFAULT_REFERENCE, String::as_str),
        }
    }

    /// The time steps dt_min dt_factor^k up to dt_max (within a relative 1e-9).
    pub fn grid(&self) -> Vec<f64> {
        (0..)
            .map(|k| self.dt_min * self.dt_factor.powi(k))
            .take_while(|&dt| dt <= self.dt_max * (1.0 + 1e-9))
            .collect()
    }

    /// Time step of the baseline run.
    pub fn baseline_dt(&self) -> f64 {
        self.baseline_dt.unwrap_or(self.dt_min)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_is_geometric_and_inclusive() {
        let w = SweepSpec {
            dt_min: 0.01,
            dt_max: 0.04,
            dt_factor: 2.0,
            ..Default::default()
        };
        assert_eq!(w.grid(), vec![0.01, 0.02, 0.04]);
    }

    /// `dpd sweep --schemes aboba` once failed: the default reference, vv, was not swept.
    #[test]
    fn the_default_reference_is_vv_where_swept_else_the_first_scheme() {
        let with = |schemes: &[&str]| SweepSpec {
            schemes: schemes.iter().map(|s| s.to_string()).collect(),
            ..Default::default()
        };
        assert_eq!(with(&["aboba", "vv"]).reference(), "vv");
        assert_eq!(with(&["aboba"]).reference(), "aboba");
        assert_eq!(with(&["baoab", "aboba"]).reference(), "baoab");
        with(&["aboba"]).validate(10.0, false, false).unwrap();
        let named = SweepSpec {
            reference: Some("vv".into()),
            ..with(&["aboba"])
        };
        let e = named.validate(10.0, false, false).unwrap_err();
        assert_eq!(e.field, "sweep.reference");
    }
}
