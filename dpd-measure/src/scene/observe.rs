//! The observe section: what a run measures besides the thermodynamics that every run averages
//! (the observers of `crate::observer` that each table switches on).

use super::check::{positive, require};
use dpd_core::ParamError;
use serde::{Deserialize, Serialize};

/// Tables `[rdf]`, `[vacf]`, `[profile]` and the keys `energy_balance`, `like_neighbours`,
/// `processing`; a scene without them does not pay for them.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Observe {
    pub rdf: Option<RdfSpec>,
    pub vacf: Option<VacfSpec>,
    pub profile: Option<ProfileSpec>,
    /// Measure the heat and the shadow work over the averaging window (schemes made of A, B,
    /// O and Ob, at equilibrium; see `dpd_core::observe::EnergyBalance`).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub energy_balance: bool,
    /// With `[[species]]`: the fraction of like neighbours within r_c of each species (a pass
    /// over the pairs at every sample).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub like_neighbours: bool,
    /// `c` of the position processor: T_C, the potential energy and the pressure's virial
    /// are read at `x + c dt^2 F(x) / m` (one more force evaluation per sample, on a copy:
    /// the trajectory is unchanged). 0: at `x`, unprocessed.
    #[serde(skip_serializing_if = "is_zero")]
    pub processing: f64,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// Radial distribution function accumulated over the averaging window.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RdfSpec {
    /// Histogram range; at most half the box edge.
    pub r_max: f64,
    pub bins: usize,
    /// Time between g(r) records: every k-th sample of the averaging window, from its first,
    /// with k = max(1, round(interval / (sample steps x dt))); default every sample. A record
    /// costs an O(N^2) pass in boxes under 3 r_max, several times a step; runs that want
    /// g(r) only to draw it can record it less often than they sample T_C.
    pub interval: Option<f64>,
}

/// Velocity autocorrelation over the averaging window, reported as the diffusion coefficient.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct VacfSpec {
    /// Longest correlation time, in time units.
    pub max_lag: f64,
    /// A new time origin every this many samples.
    pub origin_every: u64,
}

/// Density, velocity and temperature in `bins` slabs across `axis` (0 = x, 1 = y, 2 = z),
/// sampled with the thermodynamics over the averaging window.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ProfileSpec {
    pub bins: usize,
    pub axis: usize,
}

impl Default for RdfSpec {
    fn default() -> Self {
        RdfSpec {
            r_max: 2.5,
            bins: 50,
            interval: None,
        }
    }
}

impl Default for VacfSpec {
    fn default() -> Self {
        VacfSpec {
            max_lag: 5.0,
            origin_every: 10,
        }
    }
}

impl Default for ProfileSpec {
    fn default() -> Self {
        ProfileSpec { bins: 20, axis: 2 }
    }
}

impl Observe {
    /// Check the tables against a box whose shortest edge is `edge`.
    pub fn validate(&self, edge: f64) -> Result<(), ParamError> {
        require(
            "processing",
            self.processing,
            self.processing.is_finite(),
            "must be a finite number (0: unprocessed)",
        )?;
        if let Some(p) = &self.profile {
            require("profile.bins", p.bins, p.bins >= 1, "must be at least 1")?;
            require(
                "profile.axis",
                p.axis,
                p.axis <= 2,
                "must be 0 (x), 1 (y) or 2 (z)",
            )?;
        }
        if let Some(r) = &self.rdf {
            let half = 0.5 * edge;
            require(
                "rdf.r_max",
                r.r_max,
                r.r_max > 0.0 && r.r_max <= half,
                &format!("must be in (0, {half:.4}] (half the box edge)"),
            )?;
            require("rdf.bins", r.bins, r.bins >= 1, "must be at least 1")?;
            if let Some(interval) = r.interval {
                positive("rdf.interval", interval)?;
            }
        }
        if let Some(v) = &self.vacf {
            positive("vacf.max_lag", v.max_lag)?;
            require(
                "vacf.origin_every",
                v.origin_every,
                v.origin_every >= 1,
                "must be at least 1",
            )?;
        }
        Ok(())
    }
}
