//! The thermodynamics every run averages over its window: T_K, T_C (a ratio of averages), the
//! potential energy per particle and the virial pressure; with `processing = c` the positional
//! ones read at `x + c dt^2 F(x) / m` (Vilmart's postprocessing, `processed_thermo`).

use super::interface::{Boxed, End, Observer, Setup};
use crate::result::RunResult;
use dpd_core::observe::{processed_thermo, thermo, ThermoAverages};
use dpd_core::{ParamError, System};

struct Thermo {
    averages: ThermoAverages,
    /// Between walls T_C and the periodic virial pressure are not the bulk quantities.
    walls: bool,
    /// `c dt^2` of the position processor (0: unprocessed).
    processing: f64,
}

pub(super) fn new<'a>(
    setup: &Setup<'a>,
    sys: &mut System,
) -> Result<Option<Boxed<'a>>, ParamError> {
    let averages = ThermoAverages::new(setup.steps, setup.scene.run.average_fraction)?;
    let walls = setup.scene.geometry.walls.is_some();
    let c = setup.scene.observe.processing;
    if c != 0.0 && sys.topology().is_some() {
        // Bonds from an init data file (the scene's own chains are refused by its check).
        return Err(ParamError::new(
            "processing",
            c,
            "the system has bonds: processing is for pair forces only (0 turns it off)",
        ));
    }
    let processing = c * setup.dt * setup.dt;
    Ok(Some(Box::new(Thermo {
        averages,
        walls,
        processing,
    })))
}

impl Observer for Thermo {
    fn sample(&mut self, sys: &mut System, _: u64) -> Result<(), ParamError> {
        let state = if self.processing == 0.0 {
            thermo(sys)
        } else {
            processed_thermo(sys, self.processing)?
        };
        self.averages.record(&state);
        Ok(())
    }

    fn finish(self: Box<Self>, _: &mut System, end: &End, result: &mut RunResult) {
        let s = self.averages.summary();
        let observed = |x: f64| (end.stable && s.samples > 0 && x.is_finite()).then_some(x);
        // Between walls the sums include frozen particles and the wall forces.
        let bulk = |x: f64| observed(x).filter(|_| !self.walls);
        result.samples = s.samples;
        result.kinetic_temperature = observed(s.kinetic_temperature);
        result.configurational_temperature = bulk(s.configurational_temperature);
        result.potential_energy = observed(s.potential_energy);
        result.pressure = bulk(s.pressure);
    }
}
