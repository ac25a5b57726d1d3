//! Results of independent runs (seeds) at one scheme and time step, combined.

use super::result::{RunResult, Viscosity};
use super::scene::Observable;
use dpd_core::observe::Running;
use serde::Serialize;
use std::collections::BTreeMap;

/// Means over the stable runs of one (scheme, dt), with the standard error of the mean of
/// the configurational temperature, and relative errors.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Aggregate {
    pub scheme: String,
    pub dt: f64,
    pub runs: usize,
    pub stable_runs: usize,
    /// Every run completed without blow-up.
    pub stable: bool,
    /// The first blow-up message, if any.
    pub error: Option<String>,
    pub kinetic_temperature: Option<f64>,
    /// Standard error of the mean over runs (this and the other `_stderr` need two stable
    /// runs).
    pub kinetic_temperature_stderr: Option<f64>,
    pub configurational_temperature: Option<f64>,
    pub configurational_temperature_stderr: Option<f64>,
    pub potential_energy: Option<f64>,
    pub potential_energy_stderr: Option<f64>,
    pub pressure: Option<f64>,
    pub pressure_stderr: Option<f64>,
    pub ms_per_step: Option<f64>,
    pub force_evaluations_per_step: Option<f64>,
    /// Mean diffusion coefficient, where the runs measured one.
    pub diffusion: Option<f64>,
    /// Mean bond length in r_c, with bonds (null without).
    pub bond_length: Option<f64>,
    pub bond_length_stderr: Option<f64>,
    /// Per species, the mean fraction of like neighbours within r_c, with `like_neighbours`
    /// (null without; a species without neighbours is left out).
    pub like_neighbours: Option<BTreeMap<String, f64>>,
    pub like_neighbours_stderr: Option<BTreeMap<String, f64>>,
    /// Mean shear viscosity with its standard error, in a sheared scene (see
    /// [`Viscosity::combine`]).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub viscosity: Option<Viscosity>,
    /// Mean heat and shadow work per particle and time unit in k_B T, where measured.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub heat: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shadow_work: Option<f64>,
    /// Mean acceptance of a Metropolis-adjusted scheme over the stable runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub acceptance: Option<f64>,
    /// (T_K - k_B T) / k_B T.
    pub kinetic_temperature_error: Option<f64>,
    /// (T_C - k_B T) / k_B T.
    pub configurational_temperature_error: Option<f64>,
    /// Relative to the baseline run (sweeps only).
    pub potential_energy_error: Option<f64>,
    pub pressure_error: Option<f64>,
    /// Relative to the baseline's mean bond length (sweeps only).
    pub bond_length_error: Option<f64>,
    /// The like-neighbour fraction's relative error against the baseline of the species that
    /// errs most, with its sign (sweeps only).
    pub like_neighbours_error: Option<f64>,
    /// (eta - eta_baseline) / eta_baseline (sweeps of a sheared scene only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shear_viscosity_relative_error: Option<f64>,
}

/// Mean of the `Some` values, `None` without any.
fn mean(values: impl Iterator<Item = Option<f64>>) -> Option<f64> {
    let mut r = Running::default();
    values.flatten().for_each(|x| r.push(x));
    (r.count() > 0).then(|| r.mean())
}

/// Standard error of the mean of the `Some` values, `None` with fewer than two.
fn stderr(values: impl Iterator<Item = Option<f64>>) -> Option<f64> {
    let mut r = Running::default();
    values.flatten().for_each(|x| r.push(x));
    (r.count() >= 2).then(|| (r.variance() / r.count() as f64).sqrt())
}

fn relative(value: Option<f64>, reference: Option<f64>) -> Option<f64> {
    let (v, r) = (value?, reference?);
    (r != 0.0).then(|| (v - r) / r.abs())
}

/// Per species, `statistic` of the like-neighbour fractions of `runs`; `None` when no run
/// measured them.
fn per_species(
    runs: &[&RunResult],
    statistic: fn(std::vec::IntoIter<Option<f64>>) -> Option<f64>,
) -> Option<BTreeMap<String, f64>> {
    let mut values: BTreeMap<&str, Vec<Option<f64>>> = BTreeMap::new();
    for fractions in runs.iter().filter_map(|r| r.like_neighbours.as_ref()) {
        for (name, f) in fractions {
            values.entry(name).or_default().push(*f);
        }
    }
    (!values.is_empty()).then(|| {
        values
            .into_iter()
            .filter_map(|(name, v)| Some((name.to_string(), statistic(v.into_iter())?)))
            .collect()
    })
}

/// The species whose value in `values` differs most, relatively, from its value in
/// `reference`, with that signed relative error.
pub fn worst_species<'a>(
    values: &'a BTreeMap<String, f64>,
    reference: &BTreeMap<String, f64>,
) -> Option<(&'a str, f64)> {
    values
        .iter()
        .filter_map(|(name, &v)| {
            Some((
                name.as_str(),
                relative(Some(v), reference.get(name).copied())?,
            ))
        })
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
}

/// The relative error of an observable in a row.
pub type RelativeError = fn(&Aggregate) -> Option<f64>;

/// The observables whose critical steps a sweep reports: their field name in the rows, their
/// label in tables, and their relative error (T_K and T_C against k_B T, the others against
/// the baseline).
pub const CRITICAL_OBSERVABLES: [(&str, &str, RelativeError); 5] = [
    ("kinetic_temperature", "T_K", |r| {
        r.kinetic_temperature_error
    }),
    ("configurational_temperature", "T_C", |r| {
        r.configurational_temperature_error
    }),
    ("potential_energy", "U", |r| r.potential_energy_error),
    ("bond_length", "bond", |r| r.bond_length_error),
    ("like_neighbours", "like", |r| r.like_neighbours_error),
];

impl Aggregate {
    /// Combine `runs` (all of one scheme and dt); temperatures are compared with `kbt`.
    pub fn of(runs: &[&RunResult], kbt: f64) -> Aggregate {
        let stable: Vec<_> = runs.iter().filter(|r| r.stable).copied().collect();
        let over = |f: fn(&RunResult) -> Option<f64>| mean(stable.iter().map(|r| f(r)));
        let spread = |f: fn(&RunResult) -> Option<f64>| stderr(stable.iter().map(|r| f(r)));
        let stable_runs: &[&RunResult] = &stable;
        let bond_length = |r: &RunResult| r.chains.as_ref().map(|c| c.bond_length);
        let kinetic_temperature = over(|r| r.kinetic_temperature);
        let configurational_temperature = over(|r| r.configurational_temperature);
        Aggregate {
            scheme: runs.first().map_or_else(String::new, |r| r.scheme.clone()),
            dt: runs.first().map_or(f64::NAN, |r| r.dt),
            runs: runs.len(),
            stable_runs: stable.len(),
            stable: stable.len() == runs.len(),
            error: runs.iter().find_map(|r| r.error.clone()),
            kinetic_temperature,
            kinetic_temperature_stderr: spread(|r| r.kinetic_temperature),
            configurational_temperature,
            configurational_temperature_stderr: spread(|r| r.configurational_temperature),
            potential_energy: over(|r| r.potential_energy),
            potential_energy_stderr: spread(|r| r.potential_energy),
            pressure: over(|r| r.pressure),
            pressure_stderr: spread(|r| r.pressure),
            ms_per_step: mean(runs.iter().map(|r| r.ms_per_step)),
            force_evaluations_per_step: mean(runs.iter().map(|r| r.force_evaluations_per_step)),
            diffusion: over(|r| r.diffusion),
            bond_length: over(bond_length),
            bond_length_stderr: spread(bond_length),
            like_neighbours: per_species(stable_runs, mean),
            like_neighbours_stderr: per_species(stable_runs, stderr),
            viscosity: Viscosity::combine(&runs.iter().map(|r| r.viscosity).collect::<Vec<_>>()),
            heat: over(|r| r.heat),
            shadow_work: over(|r| r.shadow_work),
            acceptance: over(|r| r.acceptance),
            kinetic_temperature_error: relative(kinetic_temperature, Some(kbt)),
            configurational_temperature_error: relative(configurational_temperature, Some(kbt)),
            potential_energy_error: None,
            pressure_error: None,
            bond_length_error: None,
            like_neighbours_error: None,
            shear_viscosity_relative_error: None,
        }
    }

    /// Fill the potential-energy, pressure, bond-length, like-neighbour and viscosity errors
    /// against a baseline.
    pub fn compare_with(&mut self, baseline: &Aggregate) {
        self.potential_energy_error = relative(self.potential_energy, baseline.potential_energy);
        self.pressure_error = relative(self.pressure, baseline.pressure);
        self.bond_length_error = relative(self.bond_length, baseline.bond_length);
        self.like_neighbours_error = self
            .like_neighbours
            .as_ref()
            .zip(baseline.like_neighbours.as_ref())
            .and_then(|(values, reference)| worst_species(values, reference))
            .map(|(_, e)| e);
        self.shear_viscosity_relative_error =
            relative(self.shear_viscosity(), baseline.shear_viscosity());
    }

    /// The mean shear viscosity, where measured.
    pub fn shear_viscosity(&self) -> Option<f64> {
        self.viscosity?.shear_viscosity
    }

    /// The relative error of `observable`: against k_B T for T_C, against the baseline for
    /// the viscosity.
    pub fn error_of(&self, observable: Observable) -> Option<f64> {
        match observable {
            Observable::ConfigurationalTemperature => self.configurational_temperature_error,
            Observable::Viscosity => self.shear_viscosity_relative_error,
        }
    }

    /// The error that decides the critical step: the signed relative error of `observable`,
    /// infinite when a run blew up or nothing was measured.
    pub fn critical_error(&self, observable: Observable) -> f64 {
        self.critical(self.error_of(observable))
    }

    /// `error` where every run was stable and it was measured, else infinite (a blow-up).
    pub fn critical(&self, error: Option<f64>) -> f64 {
        match (self.stable, error) {
            (true, Some(e)) => e,
            _ => f64::INFINITY,
        }
    }
}
