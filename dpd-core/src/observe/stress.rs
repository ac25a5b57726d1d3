//! Irving-Kirkwood stress and shear viscosity (algorithms.md section 6).
//!
//! `sigma = -(1/V) [ sum_i m_i (v_i - u_i) (x) (v_i - u_i) + sum_pairs q_ij (x) F_ij ]`, with
//! `u_i = rate (y_i - L_y/2) x-hat` the streaming velocity of Lees-Edwards shear (0 without
//! shear) and `F_ij` the sum of the conservative, dissipative and random pair forces; the shear
//! viscosity is `eta = <sigma_xy> / rate`.
//!
//! What "the force" of a pair is over a step of a splitting scheme needs a choice:
//! - kinetic and conservative parts: at the state at the end of the step, like every other
//!   observable (so they do not depend on where inside the step a scheme evaluates forces);
//! - dissipative and random parts: the impulses the scheme actually applied, summed over the
//!   step's O, O-BBK and T sweeps and F kicks (for T without its conservative part `a w h`) and
//!   divided by the elapsed time. The random force has no value at an instant, only an
//!   impulse over a step, and the exact O and T updates mix the dissipative and random parts
//!   in one pair impulse; the applied impulse is also what moves momentum across a plane, which
//!   is what the stress measures. A sample therefore averages these parts over all the steps
//!   since the previous sample, not only over the sampled steps.

use super::average::block_mean;
use crate::error::ParamError;
use crate::system::System;
use crate::{Tensor, Vec3};
use serde::Serialize;

/// The three parts of `sigma` at one sample, each already `-(1/V) sum ...`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stress {
    /// `-(1/V) sum_i m_i (v_i - u_i) (x) (v_i - u_i)` at the end of the step.
    pub kinetic: Tensor,
    /// `-(1/V) (sum_pairs q_ij (x) F^C_ij + the bonded virial)` at the end of the step (bonds
    /// `d (x) F`, angles `a (x) F_i + b (x) F_k` with the arms from the vertex).
    pub conservative: Tensor,
    /// `-(1/V) sum_pairs q_ij (x) (F^D_ij + F^R_ij)`, time-averaged over the steps since the
    /// previous sample from the applied pair impulses.
    pub dissipative_random: Tensor,
}

impl Stress {
    /// `sigma`, the sum of the three parts.
    pub fn total(&self) -> Tensor {
        self.kinetic + self.conservative + self.dissipative_random
    }
}

/// Measure the stress at the end of a step. The first call starts recording pair impulses
/// and returns `None`; every later call returns the stress with the dissipative and random
/// parts averaged since the previous call, or `None` if no step was taken since, or if an F
/// kick in between reused forces evaluated before recording started (velocity Verlet's first
/// half-kick after the first call). Recording costs a tensor update per pair in every sweep;
/// [`stop_recording`] ends it.
pub fn stress(sys: &mut System) -> Option<Stress> {
    let recorded = sys.restart_impulses()?;
    let elapsed = (sys.step() - recorded.since) as f64 * sys.dt();
    if !recorded.complete || elapsed <= 0.0 {
        return None;
    }
    let scale = -1.0 / sys.boundary().volume();
    Some(Stress {
        kinetic: scale * kinetic_tensor(sys),
        conservative: scale * conservative_virial(sys),
        dissipative_random: (scale / elapsed) * recorded.sum,
    })
}

/// The dissipative stress of the current state, `(1 / V) sum_pairs gamma_ij w_D r (e . v_ij) e (x) e`
/// (`v_ij` with the pair's image velocity across a sliding boundary or its wall velocity):
/// the continuous-time formula evaluated at the sampled velocities. The random force, of zero
/// mean given the state, is left out. An alternative to the applied impulses of [`stress`]:
/// both have the same mean as `dt -> 0`, and at finite `dt` they differ (docs/papers.md, 003
/// Table 6).
pub fn state_dissipative_stress(sys: &mut System) -> Tensor {
    let volume = sys.boundary().volume();
    // The pairs first: a list build re-sorts the particles.
    sys.ensure_pairs();
    let v: Vec<Vec3> = sys
        .momenta()
        .iter()
        .zip(sys.inverse_masses())
        .map(|(p, im)| p * *im)
        .collect();
    let (params, kind) = (sys.params().clone(), sys.kinds().to_vec());
    let pairs = sys.pairs();
    let shifts = pairs.shifts();
    let mut sum = Tensor::zeros();
    for (k, pair) in pairs.iter().enumerate() {
        let (ti, tj) = (kind[pair.i as usize], kind[pair.j as usize]);
        let (gamma, rc) = (params.friction(ti, tj).0, params.rc_of(ti, tj));
        let dvx = shifts.map_or(0.0, |s| s[k]);
        let u = pair.e.dot(&(v[pair.i as usize] - v[pair.j as usize])) + pair.e.x * dvx;
        sum += (gamma * pair.wr * pair.wr * pair.r(rc) * u) * pair.e * pair.e.transpose();
    }
    sum / volume
}

/// Stop recording pair impulses (the sweeps no longer pay for it).
pub fn stop_recording(sys: &mut System) {
    sys.stop_impulses();
}

/// `sum_i m_i (v_i - u_i) (x) (v_i - u_i)` with the streaming velocity `u_i` of the shear.
fn kinetic_tensor(sys: &System) -> Tensor {
    let peculiar = sys.peculiar_velocities();
    peculiar
        .iter()
        .zip(sys.masses())
        .map(|(v, &m)| m * v * v.transpose())
        .sum()
}

/// `sum_pairs q_ij (x) F^C_ij` plus the bonded virial tensor at the current positions (minimum
/// images across a sliding boundary), without moving the neighbour-list rebuilds.
fn conservative_virial(sys: &mut System) -> Tensor {
    let bonded = sys.bonded_virial_tensor();
    bonded
        + super::pair_sum(sys, |soft, pair| {
            soft.virial(pair.w) * pair.e * pair.e.transpose()
        })
}

impl System {
    /// Velocities relative to the streaming profile `u_x(y) = rate (y - L_y/2)` of the shear
    /// (the plain velocities without shear).
    pub fn peculiar_velocities(&self) -> Vec<Vec3> {
        let velocity = self
            .momenta()
            .iter()
            .zip(self.inverse_masses())
            .map(|(p, im)| p * *im);
        match self.shear() {
            None => velocity.collect(),
            Some(le) => velocity
                .zip(self.positions())
                .map(|(v, q)| {
                    let u = le.streaming_velocity(self.boundary(), q.y);
                    v - Vec3::new(u, 0.0, 0.0)
                })
                .collect(),
        }
    }
}

/// Number of blocks for the statistical error of the viscosity.
pub const VISCOSITY_BLOCKS: usize = 10;

/// Shear viscosity `eta = <sigma_xy> / rate` from samples of [`stress`].
#[derive(Clone, Debug)]
pub struct ShearViscosity {
    rate: f64,
    samples: Vec<f64>,
}

/// The measured viscosity and its standard error.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ViscositySummary {
    pub shear_viscosity: f64,
    /// Standard error from [`VISCOSITY_BLOCKS`] block averages of the `sigma_xy` samples in
    /// time order: valid when a block is much longer than the stress correlation time.
    pub shear_viscosity_error: f64,
    /// `<sigma_xy>`.
    pub stress_xy: f64,
    pub samples: u64,
}

impl ShearViscosity {
    /// A meter for `sys`, which must be sheared at a non-zero rate.
    pub fn new(sys: &System) -> Result<Self, ParamError> {
        match sys.shear() {
            Some(le) if le.rate() != 0.0 => Ok(ShearViscosity {
                rate: le.rate(),
                samples: Vec::new(),
            }),
            Some(le) => Err(ParamError::new(
                "shear_rate",
                le.rate(),
                "must be non-zero to measure a shear viscosity",
            )),
            None => Err(ParamError::new(
                "shear_rate",
                "none",
                "a shear viscosity needs Lees-Edwards boundaries (a non-zero shear rate)",
            )),
        }
    }

    /// Sample `sigma_xy` at the end of a step (see [`stress`]; the first call only starts
    /// recording). Call it every k steps, with the same k throughout.
    pub fn record(&mut self, sys: &mut System) {
        if let Some(s) = stress(sys) {
            self.push(&s);
        }
    }

    /// Add a sample measured with [`stress`] (for callers that use the stress otherwise too).
    pub fn push(&mut self, stress: &Stress) {
        self.samples.push(stress.total()[(0, 1)]);
    }

    pub fn samples(&self) -> u64 {
        self.samples.len() as u64
    }

    /// The viscosity with its error; `None` with fewer than [`VISCOSITY_BLOCKS`] samples.
    pub fn summary(&self) -> Option<ViscositySummary> {
        let (stress_xy, error) = block_mean(&self.samples, VISCOSITY_BLOCKS)?;
        let rate = self.rate.abs();
        Some(ViscositySummary {
            shear_viscosity: stress_xy / self.rate,
            shear_viscosity_error: error / rate,
            stress_xy,
            samples: self.samples(),
        })
    }
}
