use crate::error::ParamError;
use crate::system::System;
use crate::Vec3;
use std::collections::VecDeque;

/// Velocity autocorrelation `C(t) = <v(t) . v(0)>` (averaged over particles and time origins)
/// and the diffusion coefficient `D = (1/3) integral C(t) dt` (trapezoid rule).
#[derive(Clone, Debug)]
pub struct Vacf {
    max_lag: usize,
    origin_every: u64,
    origins: VecDeque<(u64, Vec<Vec3>)>,
    sums: Vec<f64>,
    counts: Vec<u64>,
    samples: u64,
}

impl Vacf {
    /// Correlate up to `max_lag` samples apart, with a new time origin every `origin_every`
    /// samples.
    pub fn new(max_lag: usize, origin_every: u64) -> Result<Self, ParamError> {
        if origin_every == 0 {
            return Err(ParamError::new(
                "vacf.origin_every",
                0,
                "must be at least 1",
            ));
        }
        Ok(Vacf {
            max_lag,
            origin_every,
            origins: VecDeque::new(),
            sums: vec![0.0; max_lag + 1],
            counts: vec![0; max_lag + 1],
            samples: 0,
        })
    }

    /// Add the velocities of the current state as the next sample, indexed by particle id
    /// (the storage order changes at neighbour-list builds).
    pub fn record(&mut self, sys: &System) {
        let mut v = vec![Vec3::zeros(); sys.len()];
        for ((&id, p), m) in sys.ids().iter().zip(sys.momenta()).zip(sys.masses()) {
            v[id as usize] = p / *m;
        }
        self.record_velocities(v);
    }

    /// Add one sample of per-particle velocities.
    pub fn record_velocities(&mut self, v: Vec<Vec3>) {
        let s = self.samples;
        while self
            .origins
            .front()
            .is_some_and(|(t0, _)| s - t0 > self.max_lag as u64)
        {
            self.origins.pop_front();
        }
        let n = v.len().max(1) as f64;
        for (t0, v0) in &self.origins {
            let lag = (s - t0) as usize;
            self.sums[lag] += v.iter().zip(v0).map(|(a, b)| a.dot(b)).sum::<f64>() / n;
            self.counts[lag] += 1;
        }
        if s.is_multiple_of(self.origin_every) {
            self.sums[0] += v.iter().map(|a| a.norm_squared()).sum::<f64>() / n;
            self.counts[0] += 1;
            self.origins.push_back((s, v));
        }
        self.samples += 1;
    }

    /// `C` at lags `0..=max_lag` samples (NaN where no origin reached that lag).
    pub fn correlation(&self) -> Vec<f64> {
        self.sums
            .iter()
            .zip(&self.counts)
            .map(|(s, &c)| if c == 0 { f64::NAN } else { s / c as f64 })
            .collect()
    }

    /// `D = (1/3) integral_0^{max_lag * interval} C(t) dt`, with `interval` the time between
    /// samples.
    pub fn diffusion(&self, interval: f64) -> f64 {
        let c = self.correlation();
        let integral: f64 = c.windows(2).map(|w| 0.5 * (w[0] + w[1]) * interval).sum();
        integral / 3.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exponential_decay_gives_its_integral() {
        // Velocities decaying as exp(-t/tau) from every origin: C(t) = <v0^2> exp(-t/tau).
        // Each origin restarts from v0, so record blocks of (max_lag + 1) samples.
        let (tau, dt, max_lag) = (0.5, 0.01, 400);
        let v0 = [Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)];
        let mut vacf = Vacf::new(max_lag, (max_lag + 1) as u64).unwrap();
        for _block in 0..3 {
            for k in 0..=max_lag {
                let f = (-(k as f64) * dt / tau).exp();
                vacf.record_velocities(v0.iter().map(|v| v * f).collect());
            }
        }
        let c = vacf.correlation();
        approx::assert_relative_eq!(c[0], 2.5, epsilon = 1e-12);
        approx::assert_relative_eq!(c[100], 2.5 * (-2.0f64).exp(), epsilon = 1e-12);
        // (1/3) * 2.5 * tau * (1 - e^-8), trapezoid error O(dt^2).
        let exact = 2.5 * tau * (1.0 - (-8.0f64).exp()) / 3.0;
        approx::assert_relative_eq!(vacf.diffusion(dt), exact, max_relative = 1e-4);
    }
}
