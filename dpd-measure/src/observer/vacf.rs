//! The velocity autocorrelation over the window, reported as the diffusion coefficient.

use super::interface::{Boxed, End, Observer, Setup};
use crate::result::RunResult;
use dpd_core::observe::Vacf;
use dpd_core::{ParamError, System};

struct VacfObserver {
    vacf: Vacf,
    samples: u64,
    /// Time between samples.
    interval: f64,
}

pub(super) fn new<'a>(setup: &Setup<'a>, _: &mut System) -> Result<Option<Boxed<'a>>, ParamError> {
    let Some(spec) = &setup.scene.observe.vacf else {
        return Ok(None);
    };
    let interval = setup.interval();
    let lags = ((spec.max_lag / interval).round() as usize).max(1);
    Ok(Some(Box::new(VacfObserver {
        vacf: Vacf::new(lags, spec.origin_every)?,
        samples: 0,
        interval,
    })))
}

impl Observer for VacfObserver {
    fn sample(&mut self, sys: &mut System, _: u64) -> Result<(), ParamError> {
        self.vacf.record(sys);
        self.samples += 1;
        Ok(())
    }

    fn finish(self: Box<Self>, _: &mut System, end: &End, result: &mut RunResult) {
        result.diffusion = (end.stable && self.samples > 0)
            .then(|| self.vacf.diffusion(self.interval))
            .filter(|d| d.is_finite());
    }
}
