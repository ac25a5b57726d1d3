use super::thermo::Thermo;
use crate::error::ParamError;
use serde::Serialize;

/// Running mean and variance of a scalar (Welford's update).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Running {
    n: u64,
    mean: f64,
    m2: f64,
}

impl Running {
    pub fn push(&mut self, x: f64) {
        self.n += 1;
        let d = x - self.mean;
        self.mean += d / self.n as f64;
        self.m2 += d * (x - self.mean);
    }
    pub fn count(&self) -> u64 {
        self.n
    }
    /// Mean of the values pushed (NaN when none).
    pub fn mean(&self) -> f64 {
        if self.n == 0 {
            f64::NAN
        } else {
            self.mean
        }
    }
    /// Sample variance (NaN with fewer than two values).
    pub fn variance(&self) -> f64 {
        if self.n < 2 {
            f64::NAN
        } else {
            self.m2 / (self.n - 1) as f64
        }
    }
}

/// Mean of a time series and its standard error from `blocks` consecutive blocks of equal
/// length: `sd(block means) / sqrt(blocks)`, valid when a block is much longer than the
/// correlation time of the series. The first `len % blocks` values are left out so that the
/// blocks are equal. `None` with fewer than `blocks` values or fewer than 2 blocks.
pub fn block_mean(values: &[f64], blocks: usize) -> Option<(f64, f64)> {
    if blocks < 2 || values.len() < blocks {
        return None;
    }
    let len = values.len() / blocks;
    let mut means = Running::default();
    for block in values[values.len() % blocks..].chunks_exact(len) {
        means.push(block.iter().sum::<f64>() / len as f64);
    }
    Some((means.mean(), (means.variance() / blocks as f64).sqrt()))
}

/// The standard error of the ratio `sum numerator / sum denominator` of two time series
/// sampled together (k_B T_C's sums), from `blocks` consecutive blocks of equal length: the
/// standard deviation of the blocks' ratios over `sqrt(blocks)`, valid as for [`block_mean`].
/// The first `len % blocks` samples are left out so that the blocks are equal. `None` with
/// fewer than `blocks` samples or fewer than 2 blocks.
pub fn block_ratio_error(numerator: &[f64], denominator: &[f64], blocks: usize) -> Option<f64> {
    let n = numerator.len().min(denominator.len());
    if blocks < 2 || n < blocks {
        return None;
    }
    let (len, skip) = (n / blocks, n % blocks);
    let mut ratios = Running::default();
    for (num, den) in numerator[skip..n]
        .chunks_exact(len)
        .zip(denominator[skip..n].chunks_exact(len))
    {
        ratios.push(num.iter().sum::<f64>() / den.iter().sum::<f64>());
    }
    Some((ratios.variance() / blocks as f64).sqrt())
}

/// Averages of [`Thermo`] samples over the last `fraction` of a run of `total_steps` steps.
#[derive(Clone, Debug)]
pub struct ThermoAverages {
    start_step: u64,
    kinetic: Running,
    numerator: Running,
    denominator: Running,
    potential: Running,
    pressure: Running,
}

/// Averaged observables of a run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ThermoSummary {
    pub samples: u64,
    pub kinetic_temperature: f64,
    /// `<sum |F^C|^2> / <sum lap U>`: a ratio of averages, not an average of ratios.
    pub configurational_temperature: f64,
    pub potential_energy: f64,
    pub pressure: f64,
}

impl ThermoAverages {
    /// Average over steps `>= (1 - fraction) * total_steps`; `fraction` in `(0, 1]`.
    pub fn new(total_steps: u64, fraction: f64) -> Result<Self, ParamError> {
        if !(fraction > 0.0 && fraction <= 1.0) {
            return Err(ParamError::new(
                "average_fraction",
                fraction,
                "must be in (0, 1]",
            ));
        }
        let start_step = ((1.0 - fraction) * total_steps as f64).round() as u64;
        Ok(ThermoAverages {
            start_step,
            kinetic: Running::default(),
            numerator: Running::default(),
            denominator: Running::default(),
            potential: Running::default(),
            pressure: Running::default(),
        })
    }

    /// First step counted.
    pub fn start_step(&self) -> u64 {
        self.start_step
    }

    /// Whether a state after `completed_steps` steps falls into the averaging window.
    pub fn wants(&self, completed_steps: u64) -> bool {
        completed_steps >= self.start_step
    }

    pub fn record(&mut self, t: &Thermo) {
        self.kinetic.push(t.kinetic_temperature);
        self.numerator.push(t.config_numerator);
        self.denominator.push(t.config_denominator);
        self.potential.push(t.potential_energy);
        self.pressure.push(t.pressure);
    }

    pub fn summary(&self) -> ThermoSummary {
        ThermoSummary {
            samples: self.kinetic.count(),
            kinetic_temperature: self.kinetic.mean(),
            configurational_temperature: self.numerator.mean() / self.denominator.mean(),
            potential_energy: self.potential.mean(),
            pressure: self.pressure.mean(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn welford_matches_two_pass() {
        let xs = [1.0, 4.0, 9.0, 16.0, 25.0];
        let mut r = Running::default();
        xs.iter().for_each(|&x| r.push(x));
        assert_eq!(r.mean(), 11.0);
        approx::assert_relative_eq!(r.variance(), 93.5);
    }

    #[test]
    fn block_error_of_independent_blocks() {
        // Blocks with means 1, 2, 3, 4 (two values each): mean 2.5, sd of means sqrt(5/3),
        // standard error sqrt(5/3) / 2.
        let values = [9.0, 0.5, 1.5, 2.0, 2.0, 2.5, 3.5, 4.0, 4.0];
        let (mean, error) = block_mean(&values, 4).unwrap();
        assert_eq!(mean, 2.5);
        approx::assert_relative_eq!(error, (5.0f64 / 3.0).sqrt() / 2.0);
        assert_eq!(block_mean(&values[..3], 4), None);
    }

    #[test]
    fn block_ratio_error_is_the_spread_of_the_blocks_ratios() {
        // Blocks (2, 2) / (1, 1) and (6, 6) / (2, 2) after the left-out first sample: ratios 2
        // and 3, whose standard deviation is sqrt(1/2), so the error is 1/2. With denominators
        // 1 the blocks' ratios are their means: the error of block_mean.
        let (num, den) = ([7.0, 2.0, 2.0, 6.0, 6.0], [5.0, 1.0, 1.0, 2.0, 2.0]);
        approx::assert_relative_eq!(block_ratio_error(&num, &den, 2).unwrap(), 0.5);
        let values = [9.0, 0.5, 1.5, 2.0, 2.0, 2.5, 3.5, 4.0, 4.0];
        let error = block_ratio_error(&values, &[1.0; 9], 4).unwrap();
        approx::assert_relative_eq!(error, block_mean(&values, 4).unwrap().1);
        assert_eq!(block_ratio_error(&num[..1], &den[..1], 2), None);
    }

    #[test]
    fn window_is_the_last_fraction() {
        let a = ThermoAverages::new(1000, 0.8).unwrap();
        assert_eq!(a.start_step(), 200);
        assert!(!a.wants(199) && a.wants(200));
        assert_eq!(
            ThermoAverages::new(10, 1.5).unwrap_err().field,
            "average_fraction"
        );
    }
}
