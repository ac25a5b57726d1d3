//! The run section: the scheme, the time step, how long, how often to sample, the seeds and
//! the threads.

use super::check::{cores, positive, require, steps_in_range, MAX_THREADS_PER_CORE};
use dpd_core::ParamError;
use serde::{Deserialize, Serialize};

/// Keys `scheme`, `allow_inconsistent`, `dt`, `time`, `average_fraction`, `sample_interval`,
/// `seed`, `runs`, `threads`. Times in reduced time units.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RunSpec {
    /// Registry name or scheme string, for `dpd run`.
    pub scheme: String,
    /// Run scheme strings whose coefficients the order analysis finds inconsistent (sums other
    /// than 1, e.g. M-Shardlow-1 as published) instead of refusing them; registry schemes run
    /// either way.
    pub allow_inconsistent: bool,
    /// Time step of `dpd run`.
    pub dt: f64,
    /// Length of each run in time units; steps = round(time / dt).
    pub time: f64,
    /// Observables are averaged over this last fraction of each run; the rest equilibrates.
    pub average_fraction: f64,
    /// Time between samples; a sample is taken every max(1, round(sample_interval / dt))
    /// steps, at the end of a full step.
    pub sample_interval: f64,
    /// Seed of the first run; run k uses seed + k.
    pub seed: u64,
    /// Independent runs (seeds) per scheme and dt.
    pub runs: u64,
    /// Worker threads for independent runs; 0 means one per core.
    pub threads: usize,
}

impl Default for RunSpec {
    /// The standard protocol of algorithms.md section 8: 1000 time units averaged over the
    /// last 80 %, sampled every 0.1.
    fn default() -> Self {
        RunSpec {
            scheme: "aboba".into(),
            allow_inconsistent: false,
            dt: 0.05,
            time: 1000.0,
            average_fraction: 0.8,
            sample_interval: 0.1,
            seed: 1,
            runs: 1,
            threads: 0,
        }
    }
}

impl RunSpec {
    pub fn validate(&self) -> Result<(), ParamError> {
        for (key, v) in [
            ("dt", self.dt),
            ("time", self.time),
            ("sample_interval", self.sample_interval),
        ] {
            positive(key, v)?;
        }
        let f = self.average_fraction;
        require(
            "average_fraction",
            f,
            f > 0.0 && f <= 1.0,
            "must be in (0, 1]",
        )?;
        require("runs", self.runs, self.runs >= 1, "must be at least 1")?;
        steps_in_range(self.time, "dt", self.dt)?;
        let max_threads = MAX_THREADS_PER_CORE * cores();
        require(
            "threads",
            self.threads,
            self.threads <= max_threads,
            &format!(
                "must be at most {max_threads} ({MAX_THREADS_PER_CORE} per core of this \
                 machine; 0 means one per core)"
            ),
        )
    }

    /// Steps of a run at `dt`: round(time / dt), which [`RunSpec::validate`] keeps between 1
    /// and `MAX_STEPS` (at least 1 here too).
    pub fn steps(&self, dt: f64) -> u64 {
        ((self.time / dt).round() as u64).max(1)
    }

    /// Steps between samples at `dt` (at least 1).
    pub fn sample_every(&self, dt: f64) -> u64 {
        ((self.sample_interval / dt).round() as u64).max(1)
    }

    /// The seeds of the runs: `seed`, `seed + 1`, ...
    pub fn seeds(&self) -> std::ops::Range<u64> {
        self.seed..self.seed + self.runs
    }

    /// Workers for `jobs` independent runs: `threads` (0: one per core).
    pub fn workers(&self) -> usize {
        match self.threads {
            0 => cores(),
            n => n,
        }
    }
}
