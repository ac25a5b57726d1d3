//! The sizes of a bonded system's chains (every system with bonds, from `[[molecules]]` or a
//! data file): the bond lengths, their mean and histogram, over every bond; the mean squared
//! end-to-end distance and radius of gyration over the linear chains (see
//! [`crate::chains::linear_chains`]), unwrapped by minimum-image bond vectors. Averages over
//! the window's samples.

use super::interface::{Boxed, End, Observer, Setup};
use crate::chains::{end_to_end_squared, gyration_squared, linear_chains, unwrapped, Chain};
use crate::result::{ChainSizes, RunResult};
use dpd_core::{ParamError, System};

/// Width of the bond-length histogram's bins, in r_c.
const BIN: f64 = 0.02;

struct Sizes {
    /// The bonds by id.
    bonds: Vec<(u32, u32)>,
    chains: Vec<Chain>,
    /// Scratch: the storage index of each id.
    at: Vec<u32>,
    /// Bond lengths per bin of width [`BIN`] (grown as needed), their sum and count.
    histogram: Vec<u64>,
    length_sum: f64,
    lengths: u64,
    /// Sums over chains and samples of R_ee^2 and R_g^2, and their count.
    end_to_end: f64,
    gyration: f64,
    chain_samples: u64,
}

pub(super) fn new<'a>(_: &Setup<'a>, sys: &mut System) -> Result<Option<Boxed<'a>>, ParamError> {
    let Some(topology) = sys.topology().filter(|t| !t.bonds().is_empty()) else {
        return Ok(None);
    };
    let bonds: Vec<(u32, u32)> = topology.bonds().iter().map(|b| (b.i, b.j)).collect();
    Ok(Some(Box::new(Sizes {
        chains: linear_chains(sys.len(), &bonds),
        bonds,
        at: vec![0; sys.len()],
        histogram: Vec::new(),
        length_sum: 0.0,
        lengths: 0,
        end_to_end: 0.0,
        gyration: 0.0,
        chain_samples: 0,
    })))
}

impl Sizes {
    fn record(&mut self, sys: &System) {
        for (k, &id) in sys.ids().iter().enumerate() {
            self.at[id as usize] = k as u32;
        }
        let (q, bx, at) = (sys.positions(), sys.boundary(), &self.at);
        let x = |id: u32| q[at[id as usize] as usize];
        for &(i, j) in &self.bonds {
            let r = bx.min_image(x(j) - x(i)).norm();
            let bin = (r / BIN) as usize;
            if bin >= self.histogram.len() {
                self.histogram.resize(bin + 1, 0);
            }
            self.histogram[bin] += 1;
            self.length_sum += r;
            self.lengths += 1;
        }
        for chain in &self.chains {
            let u = unwrapped(chain, x, bx);
            self.end_to_end += end_to_end_squared(&u);
            self.gyration += gyration_squared(&u);
            self.chain_samples += 1;
        }
    }

    fn sizes(&self) -> ChainSizes {
        let total = self.lengths as f64;
        let per_chain =
            |sum: f64| (self.chain_samples > 0).then(|| sum / self.chain_samples as f64);
        let bins = self.histogram.iter().enumerate();
        ChainSizes {
            chains: self.chains.len(),
            bond_length: self.length_sum / total,
            bond_length_histogram: bins
                .map(|(b, &c)| [(b as f64 + 0.5) * BIN, c as f64 / (total * BIN)])
                .collect(),
            end_to_end_squared: per_chain(self.end_to_end),
            gyration_squared: per_chain(self.gyration),
        }
    }
}

impl Observer for Sizes {
    fn sample(&mut self, sys: &mut System, _: u64) -> Result<(), ParamError> {
        self.record(sys);
        Ok(())
    }

    fn finish(self: Box<Self>, _: &mut System, end: &End, result: &mut RunResult) {
        result.chains = (end.stable && self.lengths > 0).then(|| self.sizes());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chains::layout;
    use crate::scene::Scene;
    use dpd_schemes::registry::resolve;

    /// A melt of 40 chains of 8 beads at its random-walk start (step 0.9): every bond is 0.9
    /// long, so the mean is 0.9 to rounding and the histogram's density (integrating to 1) is
    /// in the bins at 0.9 (0.9 / 0.02 rounds to either side of 45); R_ee^2 and R_g^2 are the means over the chains unwrapped from their ids.
    #[test]
    fn the_sizes_of_a_start_are_its_walks() {
        let text = "n = 320\n\
                    [[bond_types]]\nname = \"b\"\nstyle = \"fene\"\nk = 30.0\nr_max = 1.5\n\
                    [[molecules]]\nlength = 8\nfraction = 1.0\nbond = \"b\"\nstep = 0.9\n";
        let scene = Scene::from_toml(text, "t").unwrap();
        scene.validate().unwrap();
        let mut sys = scene.system(0.05, 1).unwrap();
        let scheme = resolve("aboba").unwrap();
        let setup = Setup {
            scene: &scene,
            scheme: scheme.as_ref(),
            dt: 0.05,
            seed: 1,
            steps: 1,
            every: 1,
        };
        let mut observer = new(&setup, &mut sys).unwrap().unwrap();
        observer.sample(&mut sys, 0).unwrap();
        let mut result = RunResult::default();
        observer.finish(&mut sys, &End { stable: true }, &mut result);
        let sizes = result.chains.unwrap();
        assert_eq!(sizes.chains, 40);
        assert!((sizes.bond_length - 0.9).abs() < 1e-12);
        let peak: Vec<_> = sizes
            .bond_length_histogram
            .iter()
            .filter(|[_, p]| *p > 0.0)
            .collect();
        assert!(peak.iter().all(|[r, _]| (r - 0.9).abs() <= BIN), "{peak:?}");
        let total: f64 = peak.iter().map(|[_, p]| p * BIN).sum();
        assert!((total - 1.0).abs() < 1e-12);
        let plans = scene.chain_plans().unwrap();
        let q = crate::chains::random_walks(&plans, sys.boundary(), 1);
        let (mut ree, mut rg) = (0.0, 0.0);
        for (chain, _) in layout(&plans) {
            let u = unwrapped(&chain, |id| q[id as usize], sys.boundary());
            ree += end_to_end_squared(&u) / 40.0;
            rg += gyration_squared(&u) / 40.0;
        }
        assert!((sizes.end_to_end_squared.unwrap() - ree).abs() < 1e-9 * ree);
        assert!((sizes.gyration_squared.unwrap() - rg).abs() < 1e-9 * rg);
    }
}
