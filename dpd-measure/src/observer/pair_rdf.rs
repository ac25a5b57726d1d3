//! The radial distribution function of each pair of species, `g_ij(r)`, over the window,
//! recorded with the total g(r) (`[rdf]` in a scene with `[[species]]`).
//!
//! `g_ij(r) = <n_ij(r, r + dr)> / (N_i N_j / V shell)` for `i != j` and
//! `<n_ii> / (N_i^2 / (2 V) shell)`, `n_ij` the unordered pairs of the two types in the shell:
//! with the composition `x_i = N_i / N`, `sum_i sum_j x_i x_j g_ij` is the total g(r) of
//! `dpd_core::observe::Rdf` term by term.

use super::interface::{Boxed, End, Observer, Setup};
use super::typed::{pair_name, type_counts, TypedPairs};
use crate::result::RunResult;
use dpd_core::{ParamError, System};
use std::collections::BTreeMap;

/// The g_ij(r) of every pair of types; also used by the Python module's `measure`.
pub struct PairRdf {
    pairs: TypedPairs,
    r_max: f64,
    bins: usize,
    /// `hist[(i * types + j) * bins + k]`, `i <= j`.
    hist: Vec<u64>,
    counts: Vec<usize>,
    volume: f64,
    names: Vec<String>,
    samples: u64,
    /// Window samples between records.
    stride: u64,
}

pub(super) fn new<'a>(
    setup: &Setup<'a>,
    sys: &mut System,
) -> Result<Option<Boxed<'a>>, ParamError> {
    let (Some(spec), Some(_)) = (&setup.scene.observe.rdf, &setup.scene.species.species) else {
        return Ok(None);
    };
    let names = setup.scene.type_names(sys.params().types());
    Ok(Some(Box::new(PairRdf {
        stride: setup.scene.rdf_stride(setup.dt),
        ..PairRdf::new(sys, spec.r_max, spec.bins, names)
    })))
}

impl PairRdf {
    /// Histograms of `bins` bins up to `r_max` of the pairs of `sys`'s types, named `names`,
    /// recorded at every sample.
    pub fn new(sys: &System, r_max: f64, bins: usize, names: Vec<String>) -> PairRdf {
        let types = names.len();
        PairRdf {
            pairs: TypedPairs::default(),
            r_max,
            bins,
            hist: vec![0; types * types * bins],
            counts: type_counts(sys, types),
            volume: sys.boundary().volume(),
            names,
            samples: 0,
            stride: 1,
        }
    }

    /// Add the pairs of `sys`'s state.
    pub fn record(&mut self, sys: &System) {
        let (types, bins) = (self.counts.len(), self.bins);
        let scale = bins as f64 / self.r_max;
        let hist = &mut self.hist;
        self.pairs.visit(sys, self.r_max, |i, j, r| {
            hist[(i * types + j) * bins + ((r * scale) as usize).min(bins - 1)] += 1;
        });
        self.samples += 1;
    }

    /// `g_ij` per pair `i <= j`, keyed `"A-B"`: `[bin centre, g]` per bin.
    pub fn g(&self) -> BTreeMap<String, Vec<[f64; 2]>> {
        let (types, bins) = (self.counts.len(), self.bins);
        let dr = self.r_max / bins as f64;
        let mut out = BTreeMap::new();
        for i in 0..types {
            for j in i..types {
                let (ni, nj) = (self.counts[i] as f64, self.counts[j] as f64);
                let pairs = if i == j { 0.5 * ni * ni } else { ni * nj };
                let rows = (0..bins)
                    .map(|k| {
                        let (r0, r1) = (k as f64 * dr, (k + 1) as f64 * dr);
                        let shell = 4.0 / 3.0 * std::f64::consts::PI * (r1.powi(3) - r0.powi(3));
                        let ideal = pairs / self.volume * shell * self.samples as f64;
                        let count = self.hist[(i * types + j) * bins + k] as f64;
                        let g = if ideal > 0.0 { count / ideal } else { 0.0 };
                        [0.5 * (r0 + r1), g]
                    })
                    .collect();
                out.insert(pair_name(&self.names, i, j), rows);
            }
        }
        out
    }
}

impl Observer for PairRdf {
    fn sample(&mut self, sys: &mut System, index: u64) -> Result<(), ParamError> {
        if index.is_multiple_of(self.stride) {
            self.record(sys);
        }
        Ok(())
    }

    fn finish(self: Box<Self>, _: &mut System, end: &End, result: &mut RunResult) {
        result.pair_rdf = (end.stable && self.samples > 0).then(|| self.g());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;
    use dpd_core::observe::Rdf;

    /// The pair RDFs of a random 30:70 mixture, weighted by the composition, add up to the
    /// total g(r) of dpd-core's own histogram (an independent pass over the pairs) in every
    /// bin, to rounding; and the unlike pair, with twice the like pairs' normalisation per
    /// pair, is not double counted: in a random mixture every g_ij is near 1 at large r.
    #[test]
    fn pair_rdfs_add_up_to_the_total_with_the_composition_weights() {
        let text = "n = 2000\ndensity = 2.0\n[[species]]\nname = \"A\"\nfraction = 0.3\n\
                    [[species]]\nname = \"B\"\nfraction = 0.7\n\
                    [pairs]\nA-A = { a = 25.0 }\nB-B = { a = 25.0 }\nA-B = { a = 25.0 }\n";
        let scene = Scene::from_toml(text, "t").unwrap();
        scene.validate().unwrap();
        let sys = scene.system(0.05, 2).unwrap();
        let mut total = Rdf::new(&sys, 3.0, 30).unwrap();
        total.record(&sys);
        let mut pairs = PairRdf::new(&sys, 3.0, 30, scene.type_names(2));
        pairs.record(&sys);
        let g = pairs.g();
        let x = [0.3, 0.7];
        for (k, (r, want)) in total.g().into_iter().enumerate() {
            let sum = x[0] * x[0] * g["A-A"][k][1]
                + 2.0 * x[0] * x[1] * g["A-B"][k][1]
                + x[1] * x[1] * g["B-B"][k][1];
            assert_eq!(g["A-B"][k][0], r);
            approx::assert_relative_eq!(sum, want, max_relative = 1e-12);
        }
        // Uniform positions: a bin from r = 1.5 expects >= 540 A-A pairs (N_A^2 / 2V x shell;
        // Poisson error <= 4.3 %, less for the others); 25 % is six standard deviations.
        for (pair, rows) in &g {
            for [r, g] in rows.iter().filter(|b| b[0] > 1.5) {
                assert!((g - 1.0).abs() < 0.25, "{pair}: g({r}) = {g}");
            }
        }
    }
}
