//! Slab profiles (density, velocity, temperature) across an axis, over the window.

use super::interface::{Boxed, End, Observer, Setup};
use crate::result::RunResult;
use dpd_core::observe::Profile;
use dpd_core::{ParamError, System};

struct ProfileObserver(Profile);

pub(super) fn new<'a>(
    setup: &Setup<'a>,
    sys: &mut System,
) -> Result<Option<Boxed<'a>>, ParamError> {
    let Some(spec) = &setup.scene.observe.profile else {
        return Ok(None);
    };
    Ok(Some(Box::new(ProfileObserver(Profile::new(
        sys, spec.axis, spec.bins,
    )?))))
}

impl Observer for ProfileObserver {
    fn sample(&mut self, sys: &mut System, _: u64) -> Result<(), ParamError> {
        self.0.record(sys);
        Ok(())
    }

    fn finish(self: Box<Self>, _: &mut System, end: &End, result: &mut RunResult) {
        result.profile = (end.stable && self.0.samples() > 0).then(|| self.0.rows());
    }
}
