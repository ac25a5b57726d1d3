//! The pair impulses a step applies, recorded for the stress ([`crate::observe::stress`]).

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
    pub(crate) fn new(step: u64) -> Self {
        ImpulseVirial {
            sum: Tensor::zeros(),
            since: step,
            complete: true,
        }
    }

    pub(crate) fn add(&mut self, virial: Tensor) {
        self.sum += virial;
    }

    /// An F kick of step `h` with the dissipative and random pair virial of its evaluation
    /// (`None`: evaluated while not recording).
    pub(crate) fn add_kick(&mut self, h: f64, virial: Option<&Tensor>) {
        match virial {
            Some(v) => self.sum += h * v,
            None => self.complete = false,
        }
    }
}
