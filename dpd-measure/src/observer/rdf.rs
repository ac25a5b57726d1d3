//! The radial distribution function over the window, recorded every `rdf_stride` samples from
//! the window's first.

use super::interface::{Boxed, End, Observer, Setup};
use crate::result::RunResult;
use dpd_core::observe::Rdf;
use dpd_core::{ParamError, System};

struct RdfObserver {
    rdf: Rdf,
    /// Window samples between records.
    stride: u64,
}

pub(super) fn new<'a>(
    setup: &Setup<'a>,
    sys: &mut System,
) -> Result<Option<Boxed<'a>>, ParamError> {
    let Some(spec) = &setup.scene.observe.rdf else {
        return Ok(None);
    };
    let rdf = Rdf::new(sys, spec.r_max, spec.bins)?;
    let stride = setup.scene.rdf_stride(setup.dt);
    Ok(Some(Box::new(RdfObserver { rdf, stride })))
}

impl Observer for RdfObserver {
    fn sample(&mut self, sys: &mut System, index: u64) -> Result<(), ParamError> {
        if index.is_multiple_of(self.stride) {
            self.rdf.record(sys);
        }
        Ok(())
    }

    fn finish(self: Box<Self>, _: &mut System, end: &End, result: &mut RunResult) {
        result.rdf = (end.stable && self.rdf.samples() > 0)
            .then(|| self.rdf.g().into_iter().map(|(r, g)| [r, g]).collect());
    }
}
