//! What the system records while it steps, for observers: the pair impulses of the dissipative
//! and random forces (for the stress, [`crate::observe::stress`]) and the heat taken up from
//! the thermostat (for the energy balance, [`crate::observe::EnergyBalance`]). The sub-flows
//! add to a recording through the methods below, the observers start, read and stop it; with
//! no recording the sweeps pay one branch.

use super::System;
use crate::Tensor;

/// Pair impulse virial `sum q_ij (x) Delta p_ij` of the dissipative and random forces, recorded
/// by the pairwise sub-flows while the system records impulses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ImpulseVirial {
    pub(crate) sum: Tensor,
    /// Step count when recording (re)started.
    pub(crate) since: u64,
    /// False when an F kick reused forces evaluated before recording started: the sum then
    /// misses that kick, and the interval is discarded.
    pub(crate) complete: bool,
}

impl ImpulseVirial {
    fn new(step: u64) -> Self {
        ImpulseVirial {
            sum: Tensor::zeros(),
            since: step,
            complete: true,
        }
    }

    fn add(&mut self, virial: Tensor) {
        self.sum += virial;
    }

    /// An F kick of step `h` with the dissipative and random pair virial of its evaluation
    /// (`None`: evaluated while not recording).
    fn add_kick(&mut self, h: f64, virial: Option<&Tensor>) {
        match virial {
            Some(v) => self.sum += h * v,
            None => self.complete = false,
        }
    }
}

/// The sub-flows' side.
impl System {
    /// Whether pair impulses are being recorded for the stress.
    pub(crate) fn recording_impulses(&self) -> bool {
        self.impulses.is_some()
    }

    /// Add a pair impulse virial to the recording (nothing when not recording).
    pub(crate) fn record_impulses(&mut self, virial: Tensor) {
        if let Some(impulses) = &mut self.impulses {
            impulses.add(virial);
        }
    }

    /// Record an F kick of step `h` with the full forces in the cache (nothing when not
    /// recording).
    pub(crate) fn record_full_kick(&mut self, h: f64) {
        if let Some(impulses) = &mut self.impulses {
            impulses.add_kick(h, self.full_virial.as_ref());
        }
    }

    /// The kinetic energy before a thermostat sweep, when heat is being recorded (`None`
    /// otherwise: the sweep then pays one branch).
    pub(crate) fn heat_mark(&self) -> Option<f64> {
        self.heat.map(|_| self.kinetic_energy())
    }

    /// Add the kinetic energy gained since `mark` ([`System::heat_mark`]) to the heat.
    pub(crate) fn record_heat(&mut self, mark: Option<f64>) {
        if let (Some(heat), Some(before)) = (self.heat, mark) {
            self.heat = Some(heat + self.kinetic_energy() - before);
        }
    }
}

/// The observers' side.
impl System {
    /// The pair impulses recorded since the last call (`None` at the first), and a new
    /// recording from the current step.
    pub(crate) fn restart_impulses(&mut self) -> Option<ImpulseVirial> {
        self.impulses.replace(ImpulseVirial::new(self.step))
    }

    /// Stop recording pair impulses, and forget the virial of the cached full forces.
    pub(crate) fn stop_impulses(&mut self) {
        self.impulses = None;
        self.full_virial = None;
    }

    /// Start recording heat from 0 (restarting a recording under way).
    pub(crate) fn start_heat(&mut self) {
        self.heat = Some(0.0);
    }

    /// The heat recorded since [`System::start_heat`], `None` when not recording.
    pub(crate) fn heat(&self) -> Option<f64> {
        self.heat
    }

    /// Stop recording heat.
    pub(crate) fn stop_heat(&mut self) {
        self.heat = None;
    }
}
