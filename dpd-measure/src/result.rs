//! What one run produced: the result a run writes, a sweep keeps and saves, and the batch
//! hands to its caller.

use dpd_core::observe::ProfileRow;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// What one run is: a scheme (registry name or scheme string), a time step and a seed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Job {
    pub scheme: String,
    pub dt: f64,
    pub seed: u64,
}

impl Job {
    /// Same scheme and seed, and dt equal to a relative 1e-9 (grids are recomputed).
    pub fn matches(&self, other: &Job) -> bool {
        self.scheme == other.scheme
            && self.seed == other.seed
            && (self.dt - other.dt).abs() <= 1e-9 * self.dt.abs().max(other.dt.abs())
    }
}

/// The outcome of one run. Observables are `None` when no sample was taken (a run that blew
/// up or was stopped before the averaging window).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RunResult {
    pub scheme: String,
    pub dt: f64,
    pub seed: u64,
    /// Steps asked for.
    pub steps: u64,
    /// Steps done without blow-up.
    pub completed_steps: u64,
    /// False when the run blew up; `error` then says where and why.
    pub stable: bool,
    pub error: Option<String>,
    /// Stopped by the user before the end; the observables cover the samples taken so far.
    pub interrupted: bool,
    /// Samples in the averages.
    pub samples: u64,
    /// k_B T_K.
    pub kinetic_temperature: Option<f64>,
    /// k_B T_C, the ratio of the averaged numerator and denominator (`None` with `[walls]`).
    pub configurational_temperature: Option<f64>,
    /// Potential energy per particle.
    pub potential_energy: Option<f64>,
    /// Virial pressure (`None` with `[walls]`).
    pub pressure: Option<f64>,
    /// Wall-clock milliseconds per step of the integration alone (no sampling). In a sheared
    /// scene this includes the recording of pair impulses for the stress, which the sweeps do
    /// during the averaging window (a tensor update per pair); with `energy_balance`, the two
    /// kinetic-energy sums per sweep of the heat recording.
    pub ms_per_step: Option<f64>,
    /// Force evaluations per step, counted during the integration.
    pub force_evaluations_per_step: Option<f64>,
    /// Pair-distance evaluations per step, counted during the integration.
    pub pair_distance_evaluations_per_step: Option<f64>,
    /// `[r, g(r)]` per bin, with `[rdf]` in the scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rdf: Option<Vec<[f64; 2]>>,
    /// With `[rdf]` and `[[species]]`: per pair of species, keyed `"A-B"`, `[r, g_AB(r)]`
    /// per bin.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pair_rdf: Option<BTreeMap<String, Vec<[f64; 2]>>>,
    /// With `like_neighbours`: per species, the fraction of its particles' neighbours within
    /// r_c that are of the same species (null for a species without neighbours).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub like_neighbours: Option<BTreeMap<String, Option<f64>>>,
    /// With bonds: the bond lengths and the sizes of the linear chains.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub chains: Option<ChainSizes>,
    /// Diffusion coefficient from the velocity autocorrelation, with `[vacf]` in the scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diffusion: Option<f64>,
    /// With a non-zero `shear_rate`: the shear viscosity and its error (null with too few
    /// samples).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viscosity: Option<Viscosity>,
    /// Slab profile with `[profile]` in the scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<Vec<ProfileRow>>,
    /// With `[profile]` and `[[species]]`: per species, `[slab centre, number density]` per
    /// slab.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub species_profile: Option<BTreeMap<String, Vec<[f64; 2]>>>,
    /// With `energy_balance`: heat taken up from the thermostat per particle and time unit, in
    /// k_B T, from the first sample of the averaging window to the end.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub heat: Option<f64>,
    /// With `energy_balance`: shadow work per particle and time unit, in k_B T, over the same
    /// window (in the steady state about minus the heat).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shadow_work: Option<f64>,
    /// With a Metropolis-adjusted scheme (`{...}`): the fraction of its accept/reject tests
    /// that kept the proposal, over the whole run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub acceptance: Option<f64>,
}

impl RunResult {
    pub fn job(&self) -> Job {
        Job {
            scheme: self.scheme.clone(),
            dt: self.dt,
            seed: self.seed,
        }
    }
}

/// The bonds and chains of a run, averaged over its samples (lengths in r_c).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ChainSizes {
    /// Linear chains (molecules whose beads form one unbranched, open path of bonds).
    pub chains: usize,
    /// Mean bond length, over every bond.
    pub bond_length: f64,
    /// `[r, p(r)]` per bin of width 0.02, from 0 to the longest bond seen: the probability
    /// density of the bond length (sum of p x 0.02 = 1).
    pub bond_length_histogram: Vec<[f64; 2]>,
    /// Mean squared end-to-end distance of the linear chains (null without any).
    pub end_to_end_squared: Option<f64>,
    /// Mean squared radius of gyration of the linear chains, equal bead weights (null without
    /// any).
    pub gyration_squared: Option<f64>,
}

/// The shear viscosity of a run; `None` values (JSON null) when too few samples were taken.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Viscosity {
    pub shear_viscosity: Option<f64>,
    /// Standard error from block averages in time.
    pub shear_viscosity_error: Option<f64>,
}

impl Viscosity {
    /// Mean over runs with the standard error of that mean from the runs' errors
    /// (`sqrt(sum e_k^2) / n`); null unless every run has a value.
    pub fn combine(runs: &[Option<Viscosity>]) -> Option<Viscosity> {
        let values: Option<Vec<(f64, f64)>> = runs
            .iter()
            .map(|v| v.and_then(|v| v.shear_viscosity.zip(v.shear_viscosity_error)))
            .collect();
        let n = runs.len() as f64;
        runs.first()?.as_ref()?;
        Some(match values {
            Some(v) if !v.is_empty() => Viscosity {
                shear_viscosity: Some(v.iter().map(|x| x.0).sum::<f64>() / n),
                shear_viscosity_error: Some(v.iter().map(|x| x.1 * x.1).sum::<f64>().sqrt() / n),
            },
            _ => Viscosity::default(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_combine_to_a_mean_with_its_error() {
        let v = |x, e| {
            Some(Viscosity {
                shear_viscosity: Some(x),
                shear_viscosity_error: Some(e),
            })
        };
        let c = Viscosity::combine(&[v(8.0, 0.3), v(6.0, 0.4)]).unwrap();
        assert_eq!(c.shear_viscosity, Some(7.0));
        assert_eq!(c.shear_viscosity_error, Some(0.25));
        let missing = Viscosity::combine(&[v(8.0, 0.3), Some(Viscosity::default())]);
        assert_eq!(missing, Some(Viscosity::default()));
        assert_eq!(Viscosity::combine(&[None]), None);
    }
}
