//! Batches: the independent runs of one scene (schemes x time steps x seeds), each distinct
//! scheme resolved once, run in parallel, every result handed to the caller as it comes (to
//! save it), all of them collected. `dpd run`, sweeps, paper items, `dpd design --measure` and
//! the Python module run their jobs through it.

use crate::result::{Job, RunResult};
use crate::runner::{lock, pool, run, Control};
use crate::scene::Scene;
use dpd_core::{ParamError, Scheme};
use dpd_ir::lang::Options;
use dpd_schemes::registry::{resolve_with, ResolveError};
use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use thiserror::Error;

/// `jobs` without those that match one before them.
pub fn distinct(jobs: impl IntoIterator<Item = Job>) -> Vec<Job> {
    let mut out: Vec<Job> = Vec::new();
    for job in jobs {
        if !out.iter().any(|j| j.matches(&job)) {
            out.push(job);
        }
    }
    out
}

/// The `jobs` that are not among `finished`.
pub fn unfinished(jobs: Vec<Job>, finished: &[RunResult]) -> Vec<Job> {
    jobs.into_iter()
        .filter(|j| !finished.iter().any(|p| p.job().matches(j)))
        .collect()
}

/// A job's scheme that is neither a registry name nor a valid scheme string.
#[derive(Debug, Error)]
#[error("{source}")]
pub struct UnknownScheme {
    pub scheme: String,
    #[source]
    pub source: ResolveError,
}

/// A scheme ready to step any number of systems at once.
pub type SharedScheme = Box<dyn Scheme + Send + Sync>;

/// Jobs of one scene with their schemes, resolved.
pub struct Batch<'s> {
    scene: &'s Scene,
    jobs: Vec<Job>,
    schemes: HashMap<String, SharedScheme>,
}

impl<'s> Batch<'s> {
    /// Resolve the scheme of every job (each distinct one once), inconsistent scheme strings
    /// only if the scene allows them (`allow_inconsistent`).
    pub fn new(scene: &'s Scene, jobs: Vec<Job>) -> Result<Batch<'s>, UnknownScheme> {
        let options = Options {
            allow_inconsistent: scene.run.allow_inconsistent,
        };
        let mut schemes = HashMap::new();
        for job in &jobs {
            if !schemes.contains_key(&job.scheme) {
                let scheme =
                    resolve_with(&job.scheme, &options).map_err(|source| UnknownScheme {
                        scheme: job.scheme.clone(),
                        source,
                    })?;
                schemes.insert(job.scheme.clone(), scheme);
            }
        }
        Ok(Batch {
            scene,
            jobs,
            schemes,
        })
    }

    pub fn jobs(&self) -> &[Job] {
        &self.jobs
    }

    /// The resolved scheme of the jobs named `name`.
    pub fn scheme(&self, name: &str) -> Option<&(dyn Scheme + Send + Sync)> {
        self.schemes.get(name).map(|s| s.as_ref())
    }

    /// Run the jobs that are not among `finished`, in the order of the list, on
    /// `scene.run.threads` workers (0: one per core): independent jobs in parallel, each on its
    /// worker's own one-thread rayon pool, or a single job on a pool of all workers. Workers are
    /// plain threads, not rayon workers: a rayon worker waiting for another pool would run
    /// other jobs meanwhile, and their time would count as the waiting job's.
    ///
    /// After every run (also an interrupted one) `save` gets every result so far, `finished`
    /// first; the same list is returned. The first invalid input stops the other runs and is
    /// returned.
    pub fn run(
        &self,
        finished: Vec<RunResult>,
        control: Control,
        save: &(dyn Fn(&[RunResult]) + Sync),
    ) -> Result<Vec<RunResult>, ParamError> {
        let pending = unfinished(self.jobs.clone(), &finished);
        let threads = self.scene.run.workers();
        let (workers, inner) = match pending.len() {
            1 => (1, threads),
            n => (threads.min(n), 1),
        };
        let points = Mutex::new(finished);
        let next = AtomicUsize::new(0);
        let first_error = Mutex::new(None);
        let fail = |e: ParamError| {
            control.stop.store(true, Ordering::Relaxed);
            lock(&first_error).get_or_insert(e);
        };
        std::thread::scope(|s| {
            for _ in 0..workers {
                s.spawn(|| {
                    let pool = match pool(inner) {
                        Ok(pool) => pool,
                        Err(e) => return fail(e),
                    };
                    while let Some(job) = pending.get(next.fetch_add(1, Ordering::Relaxed)) {
                        if control.stop.load(Ordering::Relaxed) {
                            return;
                        }
                        let scheme = &self.schemes[&job.scheme];
                        match pool.install(|| run(self.scene, job, scheme.as_ref(), control)) {
                            Ok(r) => {
                                let mut points = lock(&points);
                                points.push(r);
                                save(&points);
                            }
                            Err(e) => return fail(e),
                        }
                    }
                });
            }
        });
        match first_error.into_inner().unwrap_or_else(|e| e.into_inner()) {
            Some(e) => Err(e),
            None => Ok(points.into_inner().unwrap_or_else(|e| e.into_inner())),
        }
    }
}
