//! The shear viscosity of a sheared scene, from the stress sampled over the window (the first
//! sample only starts recording the pair impulses).

use super::interface::{Boxed, End, Observer, Setup};
use crate::result::{RunResult, Viscosity};
use dpd_core::observe::{stop_recording, ShearViscosity};
use dpd_core::{ParamError, System};

struct ViscosityObserver(ShearViscosity);

pub(super) fn new<'a>(
    setup: &Setup<'a>,
    sys: &mut System,
) -> Result<Option<Boxed<'a>>, ParamError> {
    if !setup.scene.physics.sheared() {
        return Ok(None);
    }
    Ok(Some(Box::new(ViscosityObserver(ShearViscosity::new(sys)?))))
}

impl Observer for ViscosityObserver {
    fn sample(&mut self, sys: &mut System, _: u64) -> Result<(), ParamError> {
        self.0.record(sys);
        Ok(())
    }

    fn finish(self: Box<Self>, sys: &mut System, end: &End, result: &mut RunResult) {
        stop_recording(sys);
        let s = self
            .0
            .summary()
            .filter(|s| s.shear_viscosity.is_finite() && s.shear_viscosity_error.is_finite())
            .filter(|_| end.stable);
        result.viscosity = Some(Viscosity {
            shear_viscosity: s.map(|s| s.shear_viscosity),
            shear_viscosity_error: s.map(|s| s.shear_viscosity_error),
        });
    }
}
