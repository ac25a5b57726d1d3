use crate::error::ParamError;
use crate::neighbour::CellGrid;
use crate::system::System;

/// Radial distribution function `g(r) = <n(r, r + dr)> / (4 pi r^2 rho dr)`, histogrammed
/// over `[0, r_max)` with exact shell volumes.
#[derive(Clone, Debug)]
pub struct Rdf {
    r_max: f64,
    hist: Vec<u64>,
    samples: u64,
    particles: usize,
    volume: f64,
    grid: CellGrid,
}

impl Rdf {
    /// `bins` bins up to `r_max`, which must not exceed half the shortest box edge of `sys`.
    pub fn new(sys: &System, r_max: f64, bins: usize) -> Result<Self, ParamError> {
        let half = 0.5 * sys.boundary().min_length();
        if !(r_max > 0.0 && r_max <= half) {
            return Err(ParamError::new(
                "rdf.r_max",
                r_max,
                format!("must be in (0, {half}] (half the shortest box edge)"),
            ));
        }
        if bins == 0 {
            return Err(ParamError::new("rdf.bins", bins, "must be at least 1"));
        }
        Ok(Rdf {
            r_max,
            hist: vec![0; bins],
            samples: 0,
            particles: sys.len(),
            volume: sys.boundary().volume(),
            grid: CellGrid::default(),
        })
    }

    /// Add the pair distances of the current positions.
    pub fn record(&mut self, sys: &System) {
        let (q, bx, shear) = (sys.positions(), sys.boundary(), sys.shear());
        self.grid.bin(q, bx, self.r_max);
        let pos = self.grid.gather(q);
        let scale = self.hist.len() as f64 / self.r_max;
        let hist = &mut self.hist;
        let last = hist.len() - 1;
        self.grid
            .for_each_pair(&pos, bx, shear, self.r_max, |_, _, d| {
                let r2 = d.norm_squared();
                hist[((r2.sqrt() * scale) as usize).min(last)] += 1;
            });
        self.samples += 1;
    }

    pub fn samples(&self) -> u64 {
        self.samples
    }

    /// `(bin centre, g)` per bin; all zero before the first sample.
    pub fn g(&self) -> Vec<(f64, f64)> {
        let dr = self.r_max / self.hist.len() as f64;
        let n = self.particles as f64;
        let rho = n / self.volume;
        self.hist
            .iter()
            .enumerate()
            .map(|(k, &count)| {
                let (r0, r1) = (k as f64 * dr, (k + 1) as f64 * dr);
                let shell = 4.0 / 3.0 * std::f64::consts::PI * (r1.powi(3) - r0.powi(3));
                let ideal = 0.5 * n * rho * shell * self.samples as f64;
                let g = if ideal > 0.0 {
                    count as f64 / ideal
                } else {
                    0.0
                };
                (0.5 * (r0 + r1), g)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::init::uniform_positions;
    use crate::{Params, PeriodicBox};

    #[test]
    fn ideal_gas_has_flat_rdf() {
        // 2000 uniform points in a 10^3 box: a bin [r, r + 0.1) with r >= 1 expects
        // N^2 / (2V) * 4 pi r^2 * 0.1 >= 2500 pairs, a Poisson relative error <= 2 %; 10 % is
        // five standard deviations.
        let bx = PeriodicBox::cubic(10.0).unwrap();
        let q = uniform_positions(&bx, 2000, 5);
        let sys = System::builder(Params::builder().build().unwrap(), bx, q)
            .build()
            .unwrap();
        let mut rdf = Rdf::new(&sys, 3.0, 30).unwrap();
        rdf.record(&sys);
        for (r, g) in rdf.g().into_iter().filter(|(r, _)| *r > 1.0) {
            assert!((g - 1.0).abs() < 0.1, "g({r}) = {g}");
        }
        assert_eq!(Rdf::new(&sys, 6.0, 10).unwrap_err().field, "rdf.r_max");
    }
}
