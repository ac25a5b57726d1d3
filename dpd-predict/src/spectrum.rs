//! The harmonic modes a prediction is weighted over.

use crate::anharmonic::Response;
use serde::{Deserialize, Serialize};

/// A harmonic mode in mass-weighted coordinates: `omega2` the squared frequency (the
/// eigenvalue of the mass-weighted stiffness), `gamma` the friction rate along the mode (the
/// mode's projection of the mass-weighted pair friction matrix).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Mode {
    pub omega2: f64,
    pub gamma: f64,
}

/// A mode standing for `weight` modes of a spectrum (a group of similar ones).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Weighted {
    pub mode: Mode,
    pub weight: f64,
}

/// Growth of the groups of [`Spectrum::grouped`] from the stiffest modes down.
pub const GROUP_GROWTH: f64 = 1.25;

/// The modes of a system and what the observables need to weight them: the particle count
/// (for energies per particle), the volume (for the pressure) and the temperature.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Spectrum {
    /// The modes (zero modes, such as the centre of mass, left out).
    pub modes: Vec<Mode>,
    /// Particles of the system the modes came from.
    pub particles: usize,
    /// Volume of its box, in r_c^3.
    pub volume: f64,
    /// k_B T.
    pub kbt: f64,
    /// How T_C responds to the spectrum's growth with the pairs inside the cut-off
    /// ([`crate::anharmonic`]); without it the predictions are harmonic.
    pub response: Option<Response>,
}

impl Spectrum {
    /// One oscillator of one particle in unit volume: the closed forms of Leimkuhler and
    /// Matthews are stated for it.
    pub fn oscillator(omega2: f64, gamma: f64, kbt: f64) -> Self {
        Spectrum {
            modes: vec![Mode { omega2, gamma }],
            particles: 1,
            volume: 1.0,
            kbt,
            response: None,
        }
    }

    /// The largest squared frequency (0 without modes).
    pub fn max_omega2(&self) -> f64 {
        self.modes.iter().map(|m| m.omega2).fold(0.0, f64::max)
    }

    /// The modes in groups of similar frequency, each the mean of its `omega2` and `gamma`:
    /// the mode of largest friction alone (it sets the stability of explicit frictions), then
    /// from the stiffest down, groups of 1, 1, then growing by [`GROUP_GROWTH`] every second
    /// group. The stiffest modes, which decide stability and the errors near it, stay alone;
    /// the soft ones, whose errors grow smoothly as `omega2 dt^2`, are averaged. On the
    /// standard box this makes 765 modes 43 groups and moves T_C errors at dt 0.08 by under
    /// 1 % of themselves.
    pub fn grouped(&self) -> Vec<Weighted> {
        let mut rest = self.modes.clone();
        let mut out = Vec::new();
        if let Some(k) = (0..rest.len()).max_by(|&i, &j| rest[i].gamma.total_cmp(&rest[j].gamma)) {
            out.push(Weighted {
                mode: rest.swap_remove(k),
                weight: 1.0,
            });
        }
        rest.sort_by(|a, b| b.omega2.total_cmp(&a.omega2));
        let (mut size, mut start, mut groups) = (1.0f64, 0, 0);
        while start < rest.len() {
            let end = (start + size.floor() as usize).min(rest.len());
            let group = &rest[start..end];
            let n = group.len() as f64;
            out.push(Weighted {
                mode: Mode {
                    omega2: group.iter().map(|m| m.omega2).sum::<f64>() / n,
                    gamma: group.iter().map(|m| m.gamma).sum::<f64>() / n,
                },
                weight: n,
            });
            start = end;
            groups += 1;
            if groups % 2 == 0 {
                size *= GROUP_GROWTH;
            }
        }
        out
    }
}
