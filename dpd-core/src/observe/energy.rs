//! Energy balance of a splitting scheme: heat and shadow work (algorithms.md section 6).
//!
//! A scheme whose stages are the exact flows A and B (deterministic, volume-preserving) and the
//! thermostat sweeps O and O-BBK (each pair update preserves the Maxwell-Boltzmann distribution
//! of the momenta) changes the energy `H = K + U` in two ways: the sweeps exchange *heat* with
//! the bath, `Q = sum over sweeps of their kinetic-energy change`, and the deterministic stages
//! do *shadow work* `W = Delta H - Q`, which would vanish for the exact Hamiltonian flow
//! (Sivak, Chodera and Crooks 2013). `W` is what the KL estimator of `dpd kl` averages.
//!
//! T (its pair relaxation drifts towards the conservative force, so it does not preserve the
//! Gibbs measure), F (explicit noise) and hand-written schemes have no such split; the
//! balance refuses them, and also scenes that are not at equilibrium (shear, walls, a body
//! force), where the Gibbs measure is not the target.

use crate::error::ParamError;
use crate::scheme::Scheme;
use crate::system::System;
use dpd_ir::Flow;

/// Heat and shadow work since an [`EnergyBalance`] was started, in energy units (divide by
/// `k_B T` for the dimensionless work of the fluctuation theorems).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Balance {
    /// Heat taken up from the thermostat, `Q`.
    pub heat: f64,
    /// Shadow work `W = H(now) - H(start) - Q`.
    pub shadow_work: f64,
}

/// Records heat from the moment it is started: the thermostat sweeps add their kinetic-energy
/// changes (an O(N) sum before and after each sweep, nothing when no balance runs), and the
/// shadow work follows from the energy at the start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnergyBalance {
    start: f64,
}

impl EnergyBalance {
    /// Start recording on `sys`, stepped by `scheme`, from its current state (heat 0). The
    /// system holds one recording: starting another restarts it.
    ///
    /// Errors name the stage or the scene setting for which heat and work are not defined.
    pub fn start(sys: &mut System, scheme: &dyn Scheme) -> Result<Self, ParamError> {
        balance_defined(sys, scheme)?;
        let start = hamiltonian(sys);
        sys.start_heat();
        Ok(EnergyBalance { start })
    }

    /// Heat and shadow work since the start (evaluates the potential energy).
    pub fn read(&self, sys: &mut System) -> Balance {
        let heat = sys.heat().unwrap_or(f64::NAN);
        Balance {
            heat,
            shadow_work: hamiltonian(sys) - self.start - heat,
        }
    }

    /// [`EnergyBalance::read`], then stop recording (the sweeps no longer pay for it).
    pub fn finish(self, sys: &mut System) -> Balance {
        let balance = self.read(sys);
        sys.stop_heat();
        balance
    }
}

/// Whether heat and shadow work are defined for `scheme` on `sys`: every stage is A, B, O, L or
/// O-BBK, and the scene is at equilibrium (no shear, walls or body force).
pub fn balance_defined(sys: &System, scheme: &dyn Scheme) -> Result<(), ParamError> {
    let refuse = |value: &str, why: &str| Err(ParamError::new("scheme", value, why));
    let Some(program) = scheme.program() else {
        return refuse(
            scheme.name(),
            "is hand-written: heat and shadow work are defined for schemes written in the \
             scheme language from A, B, O, Ob and L",
        );
    };
    for stage in &program.stages {
        let why = match stage.flow {
            Flow::A | Flow::B | Flow::O | Flow::Bbk | Flow::L => continue,
            Flow::T => {
                "has a T stage, which relaxes pairs towards the conservative force and so \
                 preserves neither the energy nor the Gibbs measure: its energy change is \
                 neither heat nor work (valid stages: A, B, O, Ob, L)"
            }
            Flow::F => {
                "has an F stage, an explicit stochastic kick that does not preserve the Gibbs \
                 measure: its energy change is neither heat nor work (valid stages: A, B, O, Ob, L)"
            }
            Flow::Propose | Flow::Accept => {
                "is Metropolis-adjusted: its accept/reject keeps or undoes the Hamiltonian part's \
                 energy change, which the balance of heat and shadow work does not describe \
                 (valid stages: A, B, O, Ob, L)"
            }
            Flow::Oa | Flow::On | Flow::Xi => {
                "has Oa or On and Xi, an adaptive thermostat (PAdL, PNHL), whose friction factor \
                 xi carries energy of its own (mu (xi - 1)^2 / 2, PNHL mu xi^2 / 2): the particles' energy change is neither heat nor \
                 work (valid stages: A, B, O, Ob, L)"
            }
        };
        return refuse(scheme.name(), why);
    }
    let scene = if sys.shear().is_some() {
        Some("shear_rate")
    } else if sys.walls().is_some() {
        Some("walls")
    } else if sys.body_force().is_some() {
        Some("body_force")
    } else {
        None
    };
    match scene {
        Some(key) => Err(ParamError::new(
            key,
            "set",
            "heat and shadow work are measured at equilibrium: a scene without shear, walls \
             or body force",
        )),
        None => Ok(()),
    }
}

/// `H = K + U`: kinetic plus potential energy at the current state.
pub fn hamiltonian(sys: &mut System) -> f64 {
    sys.kinetic_energy() + potential_energy(sys)
}

/// The potential energy `U = sum over pairs of phi(r_ij)` plus the bonded energy
/// ([`System::bonded_energy`]: bonds and angles, 0 without a topology).
pub fn potential_energy(sys: &mut System) -> f64 {
    sys.bonded_energy() + super::pair_sum(sys, |soft, pair| soft.energy(pair.w))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::init::equilibrium_box;
    use crate::DynScheme;

    fn system(gamma: f64, dt: f64) -> System {
        let params = crate::Params::builder().gamma(gamma).build().unwrap();
        let mut sys = equilibrium_box(params, 300, 3.0, 7)
            .unwrap()
            .dt(dt)
            .build()
            .unwrap();
        let relax = DynScheme::compile("ABOBA", "ABOBA", &Default::default()).unwrap();
        sys.advance(&relax, 200).unwrap();
        sys
    }

    /// A system in the state of `sys` (particles in its storage order) with `params`, built
    /// anew: set anything else on the builder.
    fn rebuilt(sys: &System, params: crate::Params) -> crate::SystemBuilder {
        System::builder(params, *sys.boundary(), sys.positions().to_vec())
            .momenta(sys.momenta().to_vec())
            .ids(sys.ids().to_vec())
            .seed(sys.seed())
            .dt(sys.dt())
    }

    fn scheme(source: &str) -> DynScheme {
        DynScheme::compile(source, source, &Default::default()).unwrap()
    }

    /// Without dissipation the sweeps exchange nothing, and the shadow work is the energy
    /// error of velocity Verlet. Its largest excursion over one time unit from one state falls
    /// with dt, between dt^1.4 and dt^2.6 from dt = 0.04 to 0.005: measured dt^1.70 (0.95, 0.37,
    /// 0.085, 0.028 at dt = 0.04 / 2^k), less than the dt^2 of smooth potentials because the
    /// force's derivative jumps at the cutoff. Counting a sweep's energy change as work, or
    /// leaving out U, would not fall at all.
    #[test]
    fn shadow_work_is_the_energy_error_without_thermostat() {
        let start = system(4.5, 0.02);
        let s = scheme("BAOAB");
        let largest_work = |dt: f64| {
            let without_thermostat = crate::Params::builder().gamma(0.0).build().unwrap();
            let mut sys = rebuilt(&start, without_thermostat).dt(dt).build().unwrap();
            let balance = EnergyBalance::start(&mut sys, &s).unwrap();
            let mut largest: f64 = 0.0;
            for _ in 0..(1.0 / dt).round() as u64 {
                sys.advance(&s, 1).unwrap();
                let b = balance.read(&mut sys);
                assert_eq!(b.heat, 0.0);
                largest = largest.max(b.shadow_work.abs());
            }
            largest
        };
        let slope = (largest_work(0.04) / largest_work(0.005)).ln() / 8f64.ln();
        assert!((1.4..2.6).contains(&slope), "slope {slope}");
    }

    /// With only sweeps (positions fixed) the energy change is all heat, and the shadow work
    /// is zero to rounding.
    #[test]
    fn sweeps_alone_do_no_work() {
        let mut sys = system(4.5, 0.05);
        let balance = EnergyBalance::start(&mut sys, &scheme("ABOBA")).unwrap();
        let before = sys.kinetic_energy();
        for sweep in [crate::flow::ou, crate::flow::bbk] {
            for stream in 0..5 {
                sweep(&mut sys, 0.05, stream, crate::SweepOrder::Forward);
            }
        }
        let b = balance.finish(&mut sys);
        assert!(b.heat.abs() > 1e-3, "heat {}", b.heat);
        assert!((b.heat - (sys.kinetic_energy() - before)).abs() < 1e-9);
        assert!(b.shadow_work.abs() < 1e-9, "{}", b.shadow_work);
        assert_eq!(sys.heat(), None);
    }

    #[test]
    fn refuses_stages_without_a_split_and_non_equilibrium_scenes() {
        let mut sys = system(4.5, 0.05);
        for source in ["TAT", "F A F"] {
            let e = EnergyBalance::start(&mut sys, &scheme(source)).unwrap_err();
            assert_eq!(e.field, "scheme");
            assert!(
                e.to_string().contains("valid stages: A, B, O, Ob, L"),
                "{e}"
            );
        }
        let mut sys = rebuilt(&sys, sys.params().clone())
            .body_force(crate::Vec3::new(0.1, 0.0, 0.0))
            .build()
            .unwrap();
        let e = EnergyBalance::start(&mut sys, &scheme("ABOBA")).unwrap_err();
        assert_eq!(e.field, "body_force");
        assert_eq!(sys.heat(), None);
    }
}
