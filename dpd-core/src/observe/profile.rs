//! Profiles of flows in slabs across one axis: number density, mean velocity and temperature.

use crate::error::ParamError;
use crate::system::System;
use crate::Vec3;
use serde::{Deserialize, Serialize};
use std::io::Write;

/// Slab averages along `axis` (0 = x, 1 = y, 2 = z) over the samples recorded, of the mobile
/// particles (frozen wall particles are left out):
/// - number density: particles per slab volume, averaged over samples;
/// - velocity: mass-weighted mean, `sum m v / sum m`;
/// - temperature: of the velocities relative to that mean,
///   `(sum m v.v - |sum m v|^2 / sum m) / (3 n)`, n the number of particle samples in the slab
///   (the 3 degrees of freedom the mean removes are neglected: n is large).
#[derive(Clone, Debug)]
pub struct Profile {
    axis: usize,
    length: f64,
    slab_volume: f64,
    count: Vec<u64>,
    mass: Vec<f64>,
    momentum: Vec<Vec3>,
    twice_ke: Vec<f64>,
    samples: u64,
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
            count: vec![0; bins],
            mass: vec![0.0; bins],
            momentum: vec![Vec3::zeros(); bins],
            twice_ke: vec![0.0; bins],
            samples: 0,
        })
    }

    /// Add the current state.
    pub fn record(&mut self, sys: &System) {
        let bins = self.count.len();
        let scale = bins as f64 / self.length;
        for ((q, p), (&m, &im)) in sys
            .positions()
            .iter()
            .zip(sys.momenta())
            .zip(sys.masses().iter().zip(&sys.inv_mass))
        {
            if im == 0.0 {
                continue;
            }
            let k = ((q[self.axis] * scale) as usize).min(bins - 1);
            self.count[k] += 1;
            self.mass[k] += m;
            self.momentum[k] += p;
            self.twice_ke[k] += p.norm_squared() * im;
        }
        self.samples += 1;
    }

    pub fn samples(&self) -> u64 {
        self.samples
    }

    /// The slabs in order along the axis; velocity and temperature are NaN in a slab no
    /// particle visited.
    pub fn rows(&self) -> Vec<ProfileRow> {
        let width = self.length / self.count.len() as f64;
        (0..self.count.len())
            .map(|k| {
                let n = self.count[k] as f64;
                let m = self.mass[k];
                let v = self.momentum[k] / m;
                let peculiar = self.twice_ke[k] - self.momentum[k].norm_squared() / m;
                ProfileRow {
                    position: (k as f64 + 0.5) * width,
                    density: n / (self.samples.max(1) as f64 * self.slab_volume),
                    velocity: v.into(),
                    temperature: peculiar / (3.0 * n),
                    count: self.count[k],
                }
            })
            .collect()
    }

    /// Write the rows as CSV (see [`write_profile_csv`]).
    pub fn write_csv(&self, out: impl Write) -> std::io::Result<()> {
        write_profile_csv(self.axis, &self.rows(), out)
    }
}

/// Write profile rows along `axis` (0, 1, 2) as CSV with a header line:
/// `<axis>,density,vx,vy,vz,temperature,count` (`x`, `y` or `z` first); the velocity and
/// temperature of an empty slab are empty fields.
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
    // A slab no particle visited has no velocity or temperature: empty fields, not NaN.
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
        // Velocities 1 and 3 about their mean 2: (1 + 1) / (3 * 2).
        assert_eq!(rows[0].temperature, 2.0 / 6.0);
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

    #[test]
    fn line_fit_is_exact_on_a_line() {
        let pts: Vec<(f64, f64)> = (0..5).map(|k| (k as f64, 2.0 - 0.5 * k as f64)).collect();
        let (slope, intercept) = fit_line(&pts, &[1.0, 2.0, 1.0, 3.0, 1.0]).unwrap();
        approx::assert_relative_eq!(slope, -0.5, epsilon = 1e-14);
        approx::assert_relative_eq!(intercept, 2.0, epsilon = 1e-14);
        assert_eq!(fit_line(&[(1.0, 1.0), (1.0, 2.0)], &[1.0, 1.0]), None);
    }
}
