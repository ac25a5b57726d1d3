//! A program's predicted errors on a spectrum, its stability limit and critical steps.

use crate::anharmonic;
use crate::spectrum::{Spectrum, Weighted};
use crate::stationary::{stationary_covariance, Stationary};
use crate::step_map::{StepMap, StepMapError};
use dpd_ir::Program;
use serde::Serialize;

/// The errors a program makes at one dt, exact for the harmonic modes of the spectrum, T_C's
/// with the leading anharmonic correction when the spectrum has a response
/// ([`crate::anharmonic`]).
///
/// With `ex_k = omega2_k <x_k^2> / k_B T - 1` (`x_k` processed when the predictor is,
/// [`Predictor::processed`]) and `ep_k = <p_k^2> / k_B T - 1` the relative
/// errors of mode k's configurational and kinetic variances: T_C = `<|F|^2> / <lap U>` of the
/// modes is off by `sum omega2_k ex_k / sum omega2_k`, T_K by the mean of `ep_k`, the
/// potential energy per particle by `k_B T sum ex_k / (2 N)`, and the pressure by
/// `(k_B T / V) (N ep_mean - sum ex_k / 3)`: the kinetic part, and the virial of radial
/// springs of the soft potential, whose `r f(r)` has curvature `-phi''`, so that it moves by
/// minus twice the potential energy.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Errors {
    /// (T_C - k_B T) / k_B T.
    pub configurational_temperature: f64,
    /// The anharmonic correction included in `configurational_temperature` (0 without a
    /// response).
    pub anharmonic_correction: f64,
    /// (T_K - k_B T) / k_B T.
    pub kinetic_temperature: f64,
    /// Shift of the potential energy per particle, in energy units.
    pub potential_energy: f64,
    /// Shift of the pressure.
    pub pressure: f64,
}

/// Where a relative error first reaches a threshold as dt grows.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum Critical {
    /// The error reaches the threshold at `dt`, inside the stable range.
    At { dt: f64 },
    /// The error stays below the threshold up to the stability limit `dt`, where the modes
    /// that go unstable make it infinite.
    StabilityLimit { dt: f64 },
    /// Not reached up to `dt_max` of the search.
    NotReached { dt_max: f64 },
}

impl Critical {
    /// The critical step, if found.
    pub fn dt(self) -> Option<f64> {
        match self {
            Critical::At { dt } | Critical::StabilityLimit { dt } => Some(dt),
            Critical::NotReached { .. } => None,
        }
    }
}

/// The prediction at one dt.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Row {
    pub dt: f64,
    /// Whether every mode has a stationary state (the errors are absent otherwise).
    pub stable: bool,
    #[serde(flatten)]
    pub errors: Option<Errors>,
}

/// Everything `dpd predict` prints for one program.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Prediction {
    /// Errors at the requested steps.
    pub rows: Vec<Row>,
    /// Largest dt below which every mode has a stationary state (None: stable up to the
    /// search's end).
    pub stability_limit: Option<f64>,
    pub critical_dt_10: Critical,
    pub critical_dt_1: Critical,
}

/// Smallest and largest dt the searches look at, and their grid factor; a crossing found on
/// the grid is refined by bisection to a relative 1e-6 (`REFINE`).
pub const SEARCH_DT_MIN: f64 = 1e-3;
pub const SEARCH_DT_MAX: f64 = 2.0;
const SEARCH_FACTOR: f64 = 1.03;
const REFINE: f64 = 1e-6;

/// The step at which [`Predictor::leading_processing`] cancels the error: small enough for
/// the leading term to dominate on the standard box's stiffest modes (`omega dt` about 0.16).
pub const PROCESSING_DT: f64 = 0.01;

/// Predictions of programs on one spectrum (its modes grouped, [`Spectrum::grouped`]).
#[derive(Clone, Debug)]
pub struct Predictor {
    modes: Vec<Weighted>,
    particles: f64,
    volume: f64,
    kbt: f64,
    response: Option<f64>,
    /// `c` of the position processor `x + c dt^2 F(x) / m` the observables are read at
    /// ([`Predictor::processed`]); 0: unprocessed.
    processing: f64,
}

impl Predictor {
    pub fn new(spectrum: &Spectrum) -> Self {
        Predictor {
            modes: spectrum.grouped(),
            particles: spectrum.particles.max(1) as f64,
            volume: spectrum.volume,
            kbt: spectrum.kbt,
            response: spectrum.response.map(|r| r.r),
            processing: 0.0,
        }
    }

    /// The same predictions for observables read at the processed positions `x + c dt^2
    /// F(x) / m` (Vilmart's postprocessing with one force evaluation per sample; the
    /// trajectory is unchanged). On a mode `x` is scaled by `1 - c omega2 dt^2`, so its
    /// variance by the square: exact for the harmonic part. The anharmonic correction stays
    /// that of the unprocessed measure: how processing moves T_C through the pairs entering
    /// and leaving the cut-off is not modelled.
    pub fn processed(mut self, c: f64) -> Self {
        self.processing = c;
        self
    }

    /// The processing `c` that cancels the leading `dt^2` term of the predicted T_C error, so
    /// that the processed average is of higher order (the aim of Vilmart's postprocessors):
    /// the `c` of smallest magnitude that zeroes the error at [`PROCESSING_DT`] (the error is
    /// quadratic in `c`, so three evaluations give it exactly), or the `c` of the smallest
    /// error if none does. `None` when the program is unstable there.
    pub fn leading_processing(&self, program: &Program) -> Result<Option<f64>, StepMapError> {
        let mut e = [0.0; 3];
        for (k, c) in [-1.0, 0.0, 1.0].into_iter().enumerate() {
            match self.clone().processed(c).errors(program, PROCESSING_DT)? {
                Some(errors) => e[k] = errors.configurational_temperature,
                None => return Ok(None),
            }
        }
        // e(c) = a c^2 + b c + e0.
        let (a, b, e0) = ((e[2] + e[0]) / 2.0 - e[1], (e[2] - e[0]) / 2.0, e[1]);
        let disc = b * b - 4.0 * a * e0;
        Ok(Some(if a == 0.0 {
            -e0 / b
        } else if disc < 0.0 {
            -b / (2.0 * a)
        } else {
            // The root nearer zero, in the form that does not cancel.
            2.0 * e0 / (-b - b.signum() * disc.sqrt())
        }))
    }

    /// How many groups of modes the predictions solve for.
    pub fn groups(&self) -> usize {
        self.modes.len()
    }

    /// The errors of `program` at `dt`; `Ok(None)` when a mode has no stationary state.
    pub fn errors(&self, program: &Program, dt: f64) -> Result<Option<Errors>, StepMapError> {
        let kbt = self.kbt;
        let (mut modes, mut sum_w2, mut sum_w2_ex, mut sum_ex, mut sum_ep, mut sum_slope) =
            (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for &Weighted { mode, weight } in &self.modes {
            let (map, points) = StepMap::traced(program, mode, dt, kbt)?;
            let c = match stationary_covariance(&map) {
                Stationary::Covariance(c) => c,
                Stationary::Unstable { .. } => return Ok(None),
            };
            if self.response.is_some() {
                match anharmonic::weight_slope(program, mode, dt, kbt, &c, &points)? {
                    Some(slope) => sum_slope += weight * slope,
                    None => return Ok(None),
                }
            }
            let scale = 1.0 - self.processing * mode.omega2 * dt * dt;
            let ex = mode.omega2 * scale * scale * c[(0, 0)] / kbt - 1.0;
            let ep = c[(1, 1)] / kbt - 1.0;
            modes += weight;
            sum_w2 += weight * mode.omega2;
            sum_w2_ex += weight * mode.omega2 * ex;
            sum_ex += weight * ex;
            sum_ep += weight * ep;
        }
        let n = self.particles;
        let ep_mean = if modes > 0.0 { sum_ep / modes } else { 0.0 };
        let (harmonic, anharmonic) = match (sum_w2 > 0.0, self.response) {
            (false, _) => (0.0, 0.0),
            (true, r) => (
                sum_w2_ex / sum_w2,
                r.map_or(0.0, |r| r * sum_slope / sum_w2),
            ),
        };
        Ok(Some(Errors {
            configurational_temperature: harmonic + anharmonic,
            anharmonic_correction: anharmonic,
            kinetic_temperature: ep_mean,
            potential_energy: kbt * sum_ex / (2.0 * n),
            pressure: kbt / self.volume * (n * ep_mean - sum_ex / 3.0),
        }))
    }

    /// The first dt (from [`SEARCH_DT_MIN`] up) at which a mode loses its stationary state;
    /// `None` when stable up to [`SEARCH_DT_MAX`].
    pub fn stability_limit(&self, program: &Program) -> Result<Option<f64>, StepMapError> {
        let grid = self.scan(program)?;
        self.first(program, &grid, |e| e.is_none())
    }

    /// Where |T_C error| first reaches `threshold` (a fraction: 0.1 for 10 %).
    pub fn critical_dt(&self, program: &Program, threshold: f64) -> Result<Critical, StepMapError> {
        let grid = self.scan(program)?;
        self.critical_on(program, &grid, threshold)
    }

    /// The full prediction at the steps `dts`.
    pub fn predict(&self, program: &Program, dts: &[f64]) -> Result<Prediction, StepMapError> {
        let rows = dts
            .iter()
            .map(|&dt| {
                let errors = self.errors(program, dt)?;
                Ok(Row {
                    dt,
                    stable: errors.is_some(),
                    errors,
                })
            })
            .collect::<Result<_, StepMapError>>()?;
        let grid = self.scan(program)?;
        Ok(Prediction {
            rows,
            stability_limit: self.first(program, &grid, |e| e.is_none())?,
            critical_dt_10: self.critical_on(program, &grid, 0.1)?,
            critical_dt_1: self.critical_on(program, &grid, 0.01)?,
        })
    }

    /// The errors on the geometric grid from [`SEARCH_DT_MIN`] to [`SEARCH_DT_MAX`], up to and
    /// including the first unstable point.
    fn scan(&self, program: &Program) -> Result<Vec<(f64, Option<Errors>)>, StepMapError> {
        let mut grid = Vec::new();
        let mut dt = SEARCH_DT_MIN;
        while dt <= SEARCH_DT_MAX {
            let e = self.errors(program, dt)?;
            grid.push((dt, e));
            if e.is_none() {
                break;
            }
            dt *= SEARCH_FACTOR;
        }
        Ok(grid)
    }

    fn critical_on(
        &self,
        program: &Program,
        grid: &[(f64, Option<Errors>)],
        threshold: f64,
    ) -> Result<Critical, StepMapError> {
        let reached =
            |e: Option<Errors>| e.is_none_or(|e| e.configurational_temperature.abs() >= threshold);
        Ok(match self.first(program, grid, reached)? {
            None => Critical::NotReached {
                dt_max: SEARCH_DT_MAX,
            },
            Some(dt) => {
                // Just below the crossing the error is either near the threshold (a crossing
                // in the stable range) or still small (the modes go unstable first).
                match self.errors(program, dt * (1.0 - 4.0 * REFINE))? {
                    Some(e) if e.configurational_temperature.abs() >= threshold / 2.0 => {
                        Critical::At { dt }
                    }
                    _ => Critical::StabilityLimit { dt },
                }
            }
        })
    }

    /// The smallest dt where `hit` holds: the grid's first hit, bisected against the point
    /// before it.
    fn first(
        &self,
        program: &Program,
        grid: &[(f64, Option<Errors>)],
        hit: impl Fn(Option<Errors>) -> bool,
    ) -> Result<Option<f64>, StepMapError> {
        let Some(k) = grid.iter().position(|&(_, e)| hit(e)) else {
            return Ok(None);
        };
        if k == 0 {
            return Ok(Some(grid[0].0));
        }
        let (mut lo, mut hi) = (grid[k - 1].0, grid[k].0);
        while hi - lo > REFINE * hi {
            let mid = 0.5 * (lo + hi);
            if hit(self.errors(program, mid)?) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        Ok(Some(hi))
    }
}
