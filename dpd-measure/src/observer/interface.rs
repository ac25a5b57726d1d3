//! What an observer is: the trait the runner calls and what it hands over.

use crate::result::RunResult;
use crate::scene::Scene;
use dpd_core::{ParamError, Scheme, System};

/// What an observer knows of its run when it is made.
pub struct Setup<'a> {
    pub scene: &'a Scene,
    pub scheme: &'a (dyn Scheme + Sync),
    pub dt: f64,
    pub seed: u64,
    /// Steps of the run.
    pub steps: u64,
    /// Steps between samples.
    pub every: u64,
}

impl Setup<'_> {
    /// Time between samples.
    pub fn interval(&self) -> f64 {
        self.every as f64 * self.dt
    }
}

/// How a run ended, for [`Observer::finish`].
pub struct End {
    /// No blow-up: what was sampled is a measurement (a blown-up run reports none).
    pub stable: bool,
}

/// One measurement of a run. Every method but `finish` has a default that does nothing.
pub trait Observer {
    /// The next step after `step` at which it needs the state besides the samples (a
    /// trajectory's next frame); default none.
    fn next_stop(&self, _step: u64) -> u64 {
        u64::MAX
    }

    /// The state after each chunk of steps: at every sample and every stop that any observer
    /// asked for.
    fn after_steps(&mut self, _sys: &mut System) -> Result<(), ParamError> {
        Ok(())
    }

    /// A sample of the averaging window; `index` counts the window's samples from 0.
    fn sample(&mut self, _sys: &mut System, _index: u64) -> Result<(), ParamError> {
        Ok(())
    }

    /// Put what was measured into `result`, once, after the last step (also after a blow-up
    /// or an interruption).
    fn finish(self: Box<Self>, sys: &mut System, end: &End, result: &mut RunResult);
}

/// A boxed observer of a run with set-up `'a`.
pub type Boxed<'a> = Box<dyn Observer + 'a>;
