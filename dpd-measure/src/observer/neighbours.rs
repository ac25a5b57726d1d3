//! The fraction of like neighbours of each species, the mixing order parameter of a mixture
//! (`like_neighbours = true` in a scene with `[[species]]`): of the neighbours within r_c of
//! the particles of species i, summed over the window's samples, the fraction of species i.
//!
//! In an ideal mixture (every pair the same repulsion, every type the same mass) the types are
//! labels that the dynamics does not see, so the expected fraction is `(N_i - 1) / (N - 1)`;
//! a demixing mixture has more.

use super::interface::{Boxed, End, Observer, Setup};
use super::typed::TypedPairs;
use crate::result::RunResult;
use dpd_core::{ParamError, System};
use std::collections::BTreeMap;

/// Like and all neighbours of each type; also used by the Python module's `measure`.
pub struct LikeNeighbours {
    pairs: TypedPairs,
    /// Sums over the samples, per species: neighbours of its particles of the same species,
    /// and all neighbours of its particles.
    like: Vec<u64>,
    all: Vec<u64>,
    names: Vec<String>,
    samples: u64,
}

pub(super) fn new<'a>(
    setup: &Setup<'a>,
    sys: &mut System,
) -> Result<Option<Boxed<'a>>, ParamError> {
    if !setup.scene.observe.like_neighbours {
        return Ok(None);
    }
    let names = setup.scene.type_names(sys.params().types());
    Ok(Some(Box::new(LikeNeighbours::new(names))))
}

impl LikeNeighbours {
    /// Counts of the types named `names`.
    pub fn new(names: Vec<String>) -> LikeNeighbours {
        LikeNeighbours {
            pairs: TypedPairs::default(),
            like: vec![0; names.len()],
            all: vec![0; names.len()],
            names,
            samples: 0,
        }
    }

    /// Add the neighbours within r_c of `sys`'s state.
    pub fn record(&mut self, sys: &System) {
        let (like, all) = (&mut self.like, &mut self.all);
        self.pairs.visit(sys, sys.params().rc(), |i, j, _| {
            all[i] += 1;
            all[j] += 1;
            if i == j {
                like[i] += 2;
            }
        });
        self.samples += 1;
    }

    /// Per type, the neighbours of its particles of the same type and all their neighbours,
    /// summed over the samples so far.
    pub fn sums(&self) -> (&[u64], &[u64]) {
        (&self.like, &self.all)
    }

    /// The fraction per species, keyed by name (`None` for a species without neighbours).
    fn fractions(&self) -> BTreeMap<String, Option<f64>> {
        let each = self.like.iter().zip(&self.all);
        let f = each.map(|(&l, &a)| (a > 0).then(|| l as f64 / a as f64));
        self.names.iter().cloned().zip(f).collect()
    }
}

impl Observer for LikeNeighbours {
    fn sample(&mut self, sys: &mut System, _: u64) -> Result<(), ParamError> {
        self.record(sys);
        Ok(())
    }

    fn finish(self: Box<Self>, _: &mut System, end: &End, result: &mut RunResult) {
        result.like_neighbours = (end.stable && self.samples > 0).then(|| self.fractions());
    }
}

#[cfg(test)]
mod tests {
    use crate::result::Job;
    use crate::runner::{run, Control};
    use crate::scene::Scene;
    use std::sync::atomic::AtomicBool;

    /// An ideal 1:3 mixture of N = 400 (every pair a = 25, one mass) from independent random
    /// starts: each species' like fraction is (N_i - 1) / (N - 1), 99/399 for A and 299/399
    /// for B, within four standard errors of the mean over 8 runs. The standard error is
    /// below 0.01, so a fraction of all like pairs (1/16 + 9/16 = 0.625 for both) or of the
    /// other species' neighbours would fail.
    #[test]
    fn an_ideal_mixture_has_the_composition_s_like_neighbours() {
        let text = "n = 400\ntime = 4.0\naverage_fraction = 0.5\nlike_neighbours = true\n\
                    [[species]]\nname = \"A\"\nfraction = 0.25\n\
                    [[species]]\nname = \"B\"\nfraction = 0.75\n\
                    [pairs]\nA-A = { a = 25.0 }\nB-B = { a = 25.0 }\nA-B = { a = 25.0 }\n";
        let scene = Scene::from_toml(text, "t").unwrap();
        scene.validate().unwrap();
        let aboba = dpd_schemes::registry::resolve("aboba").unwrap();
        let stop = AtomicBool::new(false);
        let control = Control {
            stop: &stop,
            progress: &|_| {},
        };
        let runs: Vec<_> = (1..=8)
            .map(|seed| {
                let job = Job {
                    scheme: "aboba".into(),
                    dt: 0.05,
                    seed,
                };
                run(&scene, &job, aboba.as_ref(), control)
                    .unwrap()
                    .like_neighbours
                    .unwrap()
            })
            .collect();
        for (name, want) in [("A", 99.0 / 399.0), ("B", 299.0 / 399.0)] {
            let f: Vec<f64> = runs.iter().map(|r| r[name].unwrap()).collect();
            let n = f.len() as f64;
            let mean = f.iter().sum::<f64>() / n;
            let var = f.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
            let se = (var / n).sqrt();
            assert!(se < 0.01, "{name}: standard error {se}");
            assert!(
                (mean - want).abs() < 4.0 * se,
                "{name}: {mean} +- {se}, want {want}"
            );
        }
    }
}
