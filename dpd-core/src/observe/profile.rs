//! Profiles of flows in slabs across one axis: number density, mean velocity and temperature.

use crate::error::ParamError;
use crate::system::System;
use crate::Vec3;
use serde::{Deserialize, Serialize};
use std::io::Write;

/// Slab averages along `axis` (0 = x, 1 = y, 2 = z) over the samples recorded, of the mobile
/// particles (frozen wall particles are left out):
/// - number density: particles per slab volume, averaged over samples;
/// - velocity: mass-weighted mean over all samples, `sum m v / sum m`;
/// - temperature: of the velocities relative to each sample's own slab mean, so a flow that
///   changes between samples (a channel still accelerating) is not counted as heat:
///   `sum_samples (sum m v.v - |sum m v|^2 / sum m) / sum_samples 3 (n - 1)`, n the slab's
///   particles in the sample (the mean removes 3 degrees of freedom per slab and sample).
#[derive(Clone, Debug)]
pub struct Profile {
    axis: usize,
    length: f64,
    slab_volume: f64,
    /// Sums of the sample being recorded, one per slab.
    sample: Vec<SlabSums>,
    total: Vec<SlabTotals>,
    samples: u64,
}

/// Sums over the particles in one slab at one sample.
#[derive(Clone, Copy, Debug, Default)]
struct SlabSums {
    count: u64,
    mass: f64,
    momentum: Vec3,
    /// `sum p.p / m`.
    twice_ke: f64,
}

/// Sums over the samples of one slab.
#[derive(Clone, Copy, Debug, Default)]
struct SlabTotals {
    count: u64,
    mass: f64,
    momentum: Vec3,
    /// Twice the kinetic energy relative to each sample's slab mean velocity.
    twice_peculiar_ke: f64,
    /// Degrees of freedom of those velocities, `3 (n - 1)` per sample.
    dof: u64,
}

impl SlabTotals {
    fn add(&mut self, s: &SlabSums) {
        self.count += s.count;
        self.mass += s.mass;
        self.momentum += s.momentum;
        if s.count > 1 {
            self.twice_peculiar_ke += s.twice_ke - s.momentum.norm_squared() / s.mass;
            self.dof += 3 * (s.count - 1);
        }
    }
}

/// One slab of a [`Profile`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ProfileRow {
    /// Centre of the slab along the axis.
    pub position: f64,
    pub density: f64,
    pub velocity: [f64; 3],
    pub temperature: f64,
    /// Particle samples in the slab (the statistical weight of the row).
    pub count: u64,
}

const AXES: [&str; 3] = ["x", "y", "z"];

impl Profile {
    /// `bins` equal slabs across the box of `sys` along `axis`.
    pub fn new(sys: &System, axis: usize, bins: usize) -> Result<Self, ParamError> {
        if axis > 2 {
            return Err(ParamError::new(
                "profile.axis",
                axis,
                "must be 0 (x), 1 (y) or 2 (z)",
            ));
        }
        if bins == 0 {
            return Err(ParamError::new("profile.bins", bins, "must be at least 1"));
        }
        let bx = sys.boundary();
        let length = bx.lengths()[axis];
        Ok(Profile {
            axis,
            length,
            slab_volume: bx.volume() / bins as f64,
            sample: vec![SlabSums::default(); bins],
            total: vec![SlabTotals::default(); bins],
            samples: 0,
        })
    }

    /// Add the current state.
    pub fn record(&mut self, sys: &System) {
        let bins = self.sample.len();
        let scale = bins as f64 / self.length;
        self.sample.fill(SlabSums::default());
        for ((q, p), (&m, &im)) in sys
            .positions()
            .iter()
            .zip(sys.momenta())
            .zip(sys.masses().iter().zip(sys.inverse_masses()))
        {
            if im == 0.0 {
                continue;
            }
            let slab = &mut self.sample[((q[self.axis] * scale) as usize).min(bins - 1)];
            slab.count += 1;
            slab.mass += m;
            slab.momentum += p;
            slab.twice_ke += p.norm_squared() * im;
        }
        for (total, sample) in self.total.iter_mut().zip(&self.sample) {
            total.add(sample);
        }
        self.samples += 1;
    }

    pub fn samples(&self) -> u64 {
        self.samples
    }

    /// The slabs in order along the axis; velocity is NaN in a slab no particle visited,
    /// temperature NaN in a slab that never held two particles at once.
    pub fn rows(&self) -> Vec<ProfileRow> {
        let width = self.length / self.total.len() as f64;
        self.total
            .iter()
            .enumerate()
            .map(|(k, t)| ProfileRow {
                position: (k as f64 + 0.5) * width,
                density: t.count as f64 / (self.samples.max(1) as f64 * self.slab_volume),
                velocity: (t.momentum / t.mass).into(),
                temperature: t.twice_peculiar_ke / t.dof as f64,
                count: t.count,
            })
            .collect()
    }

    /// Write the rows as CSV (see [`write_profile_csv`]).
    pub fn write_csv(&self, out: impl Write) -> std::io::Result<()> {
        write_profile_csv(self.axis, &self.rows(), out)
    }
}

/// Write profile rows along `axis` (0, 1, 2) as CSV with a header line:
/// `<axis>,density,vx,vy,vz,temperature,count` (`x`, `y` or `z` first); a velocity or
/// temperature that is not defined (see [`Profile::rows`]) is an empty field.
pub fn write_profile_csv(
    axis: usize,
    rows: &[ProfileRow],
    mut out: impl Write,
) -> std::io::Result<()> {
    writeln!(
        out,
        "{},density,vx,vy,vz,temperature,count",
        AXES[axis.min(2)]
    )?;
    // Undefined values are empty fields, not NaN.
    let field = |x: f64| {
        if x.is_finite() {
            x.to_string()
        } else {
            String::new()
        }
    };
    for r in rows {
        let [vx, vy, vz] = r.velocity.map(field);
        let (t, count) = (field(r.temperature), r.count);
        writeln!(
            out,
            "{},{},{vx},{vy},{vz},{t},{count}",
            r.position, r.density
        )?;
    }
    Ok(())
}

/// Least-squares line `y = intercept + slope x` through `points` weighted by `weights`; returns
/// `(slope, intercept)`, `None` with fewer than two distinct `x`.
pub fn fit_line(points: &[(f64, f64)], weights: &[f64]) -> Option<(f64, f64)> {
    let w: f64 = weights.iter().sum();
    let mean = |f: &dyn Fn(&(f64, f64)) -> f64| {
        points
            .iter()
            .zip(weights)
            .map(|(p, &wi)| wi * f(p))
            .sum::<f64>()
            / w
    };
    let (mx, my) = (mean(&|p| p.0), mean(&|p| p.1));
    let sxx = mean(&|p| (p.0 - mx) * (p.0 - mx));
    let sxy = mean(&|p| (p.0 - mx) * (p.1 - my));
    (sxx > 0.0 && w > 0.0).then(|| (sxy / sxx, my - sxy / sxx * mx))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Params, PeriodicBox};

    #[test]
    fn slabs_hold_what_was_put_in_them() {
        let bx = PeriodicBox::new([4.0, 4.0, 4.0]).unwrap();
        let q = vec![
            Vec3::new(1.0, 0.5, 1.0),
            Vec3::new(2.0, 0.7, 1.0),
            Vec3::new(1.0, 3.5, 1.0),
        ];
        let p = vec![
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(-2.0, 0.0, 0.0),
        ];
        let sys = System::builder(Params::builder().build().unwrap(), bx, q)
            .momenta(p)
            .masses(vec![1.0, 1.0, 2.0])
            .build()
            .unwrap();
        let mut profile = Profile::new(&sys, 1, 2).unwrap();
        profile.record(&sys);
        let rows = profile.rows();
        assert_eq!(rows[0].position, 1.0);
        assert_eq!(rows[0].density, 2.0 / 32.0);
        assert_eq!(rows[0].velocity, [2.0, 0.0, 0.0]);
        // Velocities 1 and 3 about their mean 2: (1 + 1) / (3 * (2 - 1)).
        assert_eq!(rows[0].temperature, 2.0 / 3.0);
        assert_eq!(rows[1].velocity, [-1.0, 0.0, 0.0]);
        let mut csv = Vec::new();
        profile.write_csv(&mut csv).unwrap();
        let csv = String::from_utf8(csv).unwrap();
        assert!(
            csv.starts_with("y,density,vx,vy,vz,temperature,count\n1,"),
            "{csv}"
        );
        // Along x in four slabs they sit in slabs 1 and 2; slabs 0 and 3 are empty.
        let mut csv = Vec::new();
        let mut along_x = Profile::new(&sys, 0, 4).unwrap();
        along_x.record(&sys);
        along_x.write_csv(&mut csv).unwrap();
        let csv = String::from_utf8(csv).unwrap();
        assert_eq!(csv.lines().nth(1), Some("0.5,0,,,,,0"), "{csv}");
        assert_eq!(csv.lines().nth(4), Some("3.5,0,,,,,0"), "{csv}");
        assert_eq!(Profile::new(&sys, 3, 2).unwrap_err().field, "profile.axis");
    }

    /// A flow that speeds up between samples is not heat: each sample's velocities are taken
    /// relative to that sample's slab mean. Against the mean over both samples (velocities 1, 3,
    /// 11, 13 about 7) the temperature would be 104 / 12 instead of 2 / 3.
    #[test]
    fn an_accelerating_flow_is_not_heat() {
        let bx = PeriodicBox::new([4.0, 4.0, 4.0]).unwrap();
        let q = vec![Vec3::new(1.0, 0.5, 1.0), Vec3::new(2.0, 0.7, 1.0)];
        let at = |v: [f64; 2]| {
            System::builder(Params::builder().build().unwrap(), bx, q.clone())
                .momenta(v.iter().map(|&v| Vec3::new(v, 0.0, 0.0)).collect())
                .build()
                .unwrap()
        };
        let (slow, fast) = (at([1.0, 3.0]), at([11.0, 13.0]));
        let mut profile = Profile::new(&slow, 1, 1).unwrap();
        profile.record(&slow);
        profile.record(&fast);
        let row = profile.rows()[0];
        assert_eq!(row.velocity, [7.0, 0.0, 0.0]);
        // (1 + 1 + 1 + 1) / (3 (2 - 1) + 3 (2 - 1)).
        assert_eq!(row.temperature, 2.0 / 3.0);
        // A slab that never held two particles at once has no temperature.
        let alone = at([1.0, 3.0]);
        let mut halves = Profile::new(&alone, 0, 4).unwrap();
        halves.record(&alone);
        assert!(halves.rows()[1].temperature.is_nan());
        assert_eq!(halves.rows()[1].velocity, [1.0, 0.0, 0.0]);
    }

    #[test]
    fn line_fit_is_exact_on_a_line() {
        let pts: Vec<(f64, f64)> = (0..5).map(|k| (k as f64, 2.0 - 0.5 * k as f64)).collect();
        let (slope, intercept) = fit_line(&pts, &[1.0, 2.0, 1.0, 3.0, 1.0]).unwrap();
        approx::assert_relative_eq!(slope, -0.5, epsilon = 1e-14);
        approx::assert_relative_eq!(intercept, 2.0, epsilon = 1e-14);
        assert_eq!(fit_line(&[(1.0, 1.0), (1.0, 2.0)], &[1.0, 1.0]), None);
    }
}
