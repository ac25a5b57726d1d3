//! `Simulation.measure`: the averages of a stretch of run with their standard errors, g(r) and
//! the velocity autocorrelation of the same samples, and in mixtures and bonded systems the
//! observables of each type and of the chains, as typed result objects.

use crate::invalid;
use crate::typed::{ChainSeries, LikeSeries};
use dpd_core::observe::{block_ratio_error, thermo, Rdf, Thermo, Vacf};
use dpd_core::{ParamError, System};
use dpd_measure::observer::{PairRdf, SpeciesProfile};
use dpd_measure::scene::{Observe, ProfileSpec, RdfSpec, VacfSpec};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict};
use pythonize::depythonize;
use serde::de::DeserializeOwned;
use std::collections::BTreeMap;

/// A mean over a run's samples and its standard error.
#[pyclass(module = "dpd", frozen, get_all)]
#[derive(Clone, Copy, Debug)]
pub struct Estimate {
    /// Mean over the samples (for T_C, the ratio of the means of its numerator and
    /// denominator).
    pub mean: f64,
    /// Standard error of `mean` from block averages: the standard deviation of the means of
    /// `blocks` consecutive blocks over sqrt(blocks); right when a block is much longer than
    /// the correlation time. None with fewer samples than blocks.
    pub stderr: Option<f64>,
}

#[pymethods]
impl Estimate {
    fn __repr__(&self) -> String {
        match self.stderr {
            Some(e) => format!("Estimate(mean={}, stderr={e})", self.mean),
            None => format!("Estimate(mean={}, stderr=None)", self.mean),
        }
    }
}

/// What `Simulation.measure` measured.
#[pyclass(module = "dpd", frozen, get_all)]
pub struct Measurement {
    /// Samples taken, one every `interval` time units.
    pub samples: u64,
    pub interval: f64,
    /// Blocks of consecutive samples behind each standard error.
    pub blocks: usize,
    /// k_B T_K.
    pub kinetic_temperature: Estimate,
    /// k_B T_C = <sum |F^C|^2> / <sum lap U>.
    pub configurational_temperature: Estimate,
    /// Potential energy per particle.
    pub potential_energy: Estimate,
    /// Virial pressure.
    pub pressure: Estimate,
    /// With `rdf`: an array of rows (r, g(r)), one per bin, r the bin's centre.
    pub rdf: Option<Py<PyArray2<f64>>>,
    /// With `vacf`: an array of rows (t, C(t)), C(t) = <v(t) . v(0)> per particle, t from 0
    /// to the longest lag in steps of `interval`.
    pub vacf: Option<Py<PyArray2<f64>>>,
    /// With `vacf`: D = (1/3) integral of C(t) dt (trapezoid rule).
    pub diffusion: Option<f64>,
    /// With `rdf` and more than one type: g_ij(r) of each pair of types i <= j, keyed "A-B",
    /// as rows (r, g_ij); with the composition x_i, sum_ij x_i x_j g_ij = g.
    pub pair_rdf: Option<Py<PyDict>>,
    /// With `like_neighbours`: per type, the fraction of its particles' neighbours within r_c
    /// that are of the same type (None for a type without neighbours).
    pub like_neighbours: Option<BTreeMap<String, Option<Estimate>>>,
    /// With `profile`: per type, rows (slab centre, number density) across the profile's axis
    /// (mobile particles only).
    pub species_profile: Option<Py<PyDict>>,
    /// With bonds: the mean bond length.
    pub bond_length: Option<Estimate>,
    /// With linear chains: the mean squared end-to-end distance and radius of gyration.
    pub end_to_end_squared: Option<Estimate>,
    pub gyration_squared: Option<Estimate>,
}

#[pymethods]
impl Measurement {
    fn __repr__(&self) -> String {
        format!(
            "Measurement(samples={}, interval={}, kinetic_temperature={}, \
             configurational_temperature={}, potential_energy={}, pressure={}, diffusion={})",
            self.samples,
            self.interval,
            self.kinetic_temperature.__repr__(),
            self.configurational_temperature.__repr__(),
            self.potential_energy.__repr__(),
            self.pressure.__repr__(),
            self.diffusion.map_or("None".into(), |d| d.to_string()),
        )
    }
}

/// The samples of a measurement as they come.
pub struct Samples {
    thermo: Vec<Thermo>,
    rdf: Option<Rdf>,
    pair_rdf: Option<PairRdf>,
    vacf: Option<Vacf>,
    like: Option<LikeSeries>,
    profile: Option<SpeciesProfile>,
    chains: Option<ChainSeries>,
    interval: f64,
    /// Steps between samples.
    pub every: u64,
}

impl Samples {
    /// Samples of `sys` every `every` steps, with the tables of `observe`; the types are
    /// named `names`.
    pub fn new(
        sys: &System,
        observe: &Observe,
        every: u64,
        names: Vec<String>,
    ) -> Result<Samples, ParamError> {
        observe.validate(sys.boundary().min_length())?;
        let interval = every as f64 * sys.dt();
        let rdf = match &observe.rdf {
            Some(r) => Some(Rdf::new(sys, r.r_max, r.bins)?),
            None => None,
        };
        let pair_rdf = match &observe.rdf {
            Some(r) if names.len() > 1 => Some(PairRdf::new(sys, r.r_max, r.bins, names.clone())),
            _ => None,
        };
        let profile = (observe.profile.as_ref())
            .map(|p| SpeciesProfile::new(sys, p.axis, p.bins, names.clone()));
        let vacf = match &observe.vacf {
            Some(v) => {
                let lags = ((v.max_lag / interval).round() as usize).max(1);
                Some(Vacf::new(lags, v.origin_every)?)
            }
            None => None,
        };
        Ok(Samples {
            thermo: Vec::new(),
            rdf,
            pair_rdf,
            vacf,
            like: observe.like_neighbours.then(|| LikeSeries::new(names)),
            profile,
            chains: ChainSeries::new(sys),
            interval,
            every,
        })
    }

    pub fn record(&mut self, sys: &mut System) {
        self.thermo.push(thermo(sys));
        if let Some(rdf) = &mut self.rdf {
            rdf.record(sys);
        }
        if let Some(pair_rdf) = &mut self.pair_rdf {
            pair_rdf.record(sys);
        }
        if let Some(vacf) = &mut self.vacf {
            vacf.record(sys);
        }
        if let Some(like) = &mut self.like {
            like.record(sys);
        }
        if let Some(profile) = &mut self.profile {
            profile.record(sys);
        }
        if let Some(chains) = &mut self.chains {
            chains.record(sys);
        }
    }

    /// The measurement of all samples so far, with standard errors from `blocks` blocks.
    pub fn finish(&self, py: Python<'_>, blocks: usize) -> PyResult<Measurement> {
        let series = |f: fn(&Thermo) -> f64| self.thermo.iter().map(f).collect::<Vec<f64>>();
        let ones = vec![1.0; self.thermo.len()];
        let mean = |values: &[f64]| ratio(values, &ones[..values.len()], blocks);
        let plain = |f: fn(&Thermo) -> f64| mean(&series(f));
        let rows = |rows: Vec<[f64; 2]>| {
            let flat: Vec<f64> = rows.iter().flatten().copied().collect();
            Array2::from_shape_vec((rows.len(), 2), flat)
                .expect("rows of 2")
                .into_pyarray(py)
                .unbind()
        };
        let dict = |map: BTreeMap<String, Vec<[f64; 2]>>| -> PyResult<Py<PyDict>> {
            let d = PyDict::new(py);
            for (name, r) in map {
                d.set_item(name, rows(r))?;
            }
            Ok(d.unbind())
        };
        let chains = self.chains.as_ref();
        let chain_mean = |v: &[f64]| (!v.is_empty()).then(|| mean(v));
        let interval = self.interval;
        let samples = !self.thermo.is_empty();
        Ok(Measurement {
            samples: self.thermo.len() as u64,
            interval,
            blocks,
            kinetic_temperature: plain(|t| t.kinetic_temperature),
            configurational_temperature: ratio(
                &series(|t| t.config_numerator),
                &series(|t| t.config_denominator),
                blocks,
            ),
            potential_energy: plain(|t| t.potential_energy),
            pressure: plain(|t| t.pressure),
            rdf: self
                .rdf
                .as_ref()
                .map(|r| rows(r.g().into_iter().map(|(r, g)| [r, g]).collect())),
            vacf: self.vacf.as_ref().map(|v| {
                let c = v.correlation().into_iter().enumerate();
                rows(c.map(|(k, c)| [k as f64 * interval, c]).collect())
            }),
            diffusion: self.vacf.as_ref().map(|v| v.diffusion(interval)),
            pair_rdf: (self.pair_rdf.as_ref())
                .filter(|_| samples)
                .map(|p| dict(p.g()))
                .transpose()?,
            like_neighbours: self.like.as_ref().map(|l| l.fractions(blocks)),
            species_profile: (self.profile.as_ref())
                .filter(|_| samples)
                .map(|p| dict(p.rows()))
                .transpose()?,
            bond_length: chains.and_then(|c| chain_mean(&c.bond_length)),
            end_to_end_squared: chains.and_then(|c| chain_mean(&c.end_to_end)),
            gyration_squared: chains.and_then(|c| chain_mean(&c.gyration)),
        })
    }
}

/// `sum(numerator) / sum(denominator)` over all the samples, with the standard error of
/// [`block_ratio_error`].
pub fn ratio(numerator: &[f64], denominator: &[f64], blocks: usize) -> Estimate {
    Estimate {
        mean: numerator.iter().sum::<f64>() / denominator.iter().sum::<f64>(),
        stderr: block_ratio_error(numerator, denominator, blocks),
    }
}

/// The table `name` of `measure(rdf=..., vacf=...)`: None keeps the scene's (`scene`), False
/// switches it off, True switches it on with the scene's keys or the defaults, a dict with the
/// keys it gives (the defaults for the others).
pub fn table<T: DeserializeOwned + Default + Clone>(
    name: &str,
    value: Option<&Bound<'_, PyAny>>,
    scene: Option<&T>,
) -> PyResult<Option<T>> {
    let Some(value) = value else {
        return Ok(scene.cloned());
    };
    if let Ok(on) = value.downcast::<PyBool>() {
        return Ok(on.is_true().then(|| scene.cloned().unwrap_or_default()));
    }
    depythonize(value)
        .map(Some)
        .map_err(|e| PyTypeError::new_err(format!("{name}: {e}")))
}

/// The tables of a measurement: `rdf`, `vacf` and `profile` as [`table`] reads them over the
/// scene's, `like_neighbours` the scene's unless given.
pub fn observe(
    scene: &Observe,
    rdf: Option<&Bound<'_, PyAny>>,
    vacf: Option<&Bound<'_, PyAny>>,
    profile: Option<&Bound<'_, PyAny>>,
    like_neighbours: Option<bool>,
) -> PyResult<Observe> {
    Ok(Observe {
        rdf: table::<RdfSpec>("rdf", rdf, scene.rdf.as_ref())?,
        vacf: table::<VacfSpec>("vacf", vacf, scene.vacf.as_ref())?,
        profile: table::<ProfileSpec>("profile", profile, scene.profile.as_ref())?,
        like_neighbours: like_neighbours.unwrap_or(scene.like_neighbours),
        ..Observe::default()
    })
}

/// Steps between samples every `interval` time units at `dt` (at least 1), or the error
/// naming `every`.
pub fn sample_steps(interval: f64, dt: f64) -> PyResult<u64> {
    if !(interval.is_finite() && interval > 0.0) {
        return Err(invalid(format!(
            "invalid every = {interval}: must be finite and > 0"
        )));
    }
    Ok(((interval / dt).round() as u64).max(1))
}
