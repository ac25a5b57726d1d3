//! The heat taken up from the thermostat and the shadow work, from the first sample of the
//! window to the end (`energy_balance`; schemes of A, B, O and Ob at equilibrium).

use super::interface::{Boxed, End, Observer, Setup};
use crate::result::RunResult;
use dpd_core::observe::{balance_defined, EnergyBalance};
use dpd_core::{ParamError, Scheme, System};

struct Energy<'a> {
    scheme: &'a (dyn Scheme + Sync),
    /// Started at the first sample of the window: the balance and its step.
    balance: Option<(EnergyBalance, u64)>,
    dt: f64,
    kbt: f64,
}

pub(super) fn new<'a>(
    setup: &Setup<'a>,
    sys: &mut System,
) -> Result<Option<Boxed<'a>>, ParamError> {
    if !setup.scene.observe.energy_balance {
        return Ok(None);
    }
    balance_defined(sys, setup.scheme)?;
    Ok(Some(Box::new(Energy {
        scheme: setup.scheme,
        balance: None,
        dt: setup.dt,
        kbt: setup.scene.physics.kbt,
    })))
}

impl Observer for Energy<'_> {
    fn sample(&mut self, sys: &mut System, _: u64) -> Result<(), ParamError> {
        if self.balance.is_none() {
            self.balance = Some((EnergyBalance::start(sys, self.scheme)?, sys.step()));
        }
        Ok(())
    }

    fn finish(self: Box<Self>, sys: &mut System, end: &End, result: &mut RunResult) {
        let Some((balance, from)) = self.balance else {
            return;
        };
        let b = balance.finish(sys);
        let steps = sys.step() - from;
        // Per particle and time unit, in k_B T.
        let scale = sys.len() as f64 * steps as f64 * self.dt * self.kbt;
        let per =
            |energy: f64| (end.stable && steps > 0 && energy.is_finite()).then(|| energy / scale);
        result.heat = per(b.heat);
        result.shadow_work = per(b.shadow_work);
    }
}
