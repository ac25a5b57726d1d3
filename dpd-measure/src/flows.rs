//! Non-equilibrium scenes (algorithms.md section 8): Lees-Edwards shear with its viscosity,
//! channels between walls across z driven by moving walls or a body force, and slab profiles.
//! A scene without `shear_rate`, `[walls]`, `body_force` or `[profile]` builds the plain
//! periodic system and samples none of this.

use super::scene::Scene;
use dpd_core::observe::{stop_recording, Profile, ProfileRow, ShearViscosity};
use dpd_core::{ParamError, System, Walls};
use serde::{Deserialize, Serialize};

/// Walls across z: the channel `lower <= z <= upper` holds the fluid, the slabs outside it
/// are filled with frozen particles at the fluid density, moving along x at `velocity`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WallSpec {
    pub lower: f64,
    pub upper: f64,
    /// x-velocities of the lower and upper wall.
    pub velocity: [f64; 2],
}

impl Default for WallSpec {
    fn default() -> Self {
        WallSpec {
            lower: 1.0,
            upper: 9.0,
            velocity: [0.0, 0.0],
        }
    }
}

impl WallSpec {
    pub fn walls(&self) -> Result<Walls, ParamError> {
        Walls::new(self.lower, self.upper, self.velocity)
    }
}

/// Density, velocity and temperature in `bins` slabs across `axis` (0 = x, 1 = y, 2 = z),
/// sampled with the thermodynamics over the averaging window.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ProfileSpec {
    pub bins: usize,
    pub axis: usize,
}

impl Default for ProfileSpec {
    fn default() -> Self {
        ProfileSpec { bins: 20, axis: 2 }
    }
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

/// The non-equilibrium observables of one run, sampled with the thermodynamics.
pub struct FlowObservers {
    viscosity: Option<ShearViscosity>,
    profile: Option<Profile>,
}

impl FlowObservers {
    /// The viscosity meter with a non-zero `shear_rate`, the profile with `[profile]`.
    pub fn new(scene: &Scene, sys: &System) -> Result<Self, ParamError> {
        let viscosity = match scene.shear_rate {
            Some(k) if k != 0.0 => Some(ShearViscosity::new(sys)?),
            _ => None,
        };
        let profile = match &scene.profile {
            Some(p) => Some(Profile::new(sys, p.axis, p.bins)?),
            None => None,
        };
        Ok(FlowObservers { viscosity, profile })
    }

    /// Sample the state at the end of a step; the first viscosity call only starts recording
    /// pair impulses.
    pub fn record(&mut self, sys: &mut System) {
        if let Some(v) = &mut self.viscosity {
            v.record(sys);
        }
        if let Some(p) = &mut self.profile {
            p.record(sys);
        }
    }

    /// Stop recording and return the viscosity (if measured) and the profile rows (if any
    /// sample was taken).
    pub fn finish(self, sys: &mut System) -> (Option<Viscosity>, Option<Vec<ProfileRow>>) {
        stop_recording(sys);
        let viscosity = self.viscosity.map(|v| {
            let s = v
                .summary()
                .filter(|s| s.shear_viscosity.is_finite() && s.shear_viscosity_error.is_finite());
            Viscosity {
                shear_viscosity: s.map(|s| s.shear_viscosity),
                shear_viscosity_error: s.map(|s| s.shear_viscosity_error),
            }
        });
        let profile = self.profile.filter(|p| p.samples() > 0).map(|p| p.rows());
        (viscosity, profile)
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
