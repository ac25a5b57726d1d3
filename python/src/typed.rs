//! The per-type and per-chain samples of `Simulation.measure`: like-neighbour counts and chain
//! sizes of each sample, whose series give block standard errors, and the pair g(r) and slab
//! densities of each type, accumulated by dpd-measure's observers of the same names.

use crate::measure::{ratio, Estimate};
use dpd_core::System;
use dpd_measure::chains::{end_to_end_squared, gyration_squared, linear_chains, unwrapped, Chain};
use dpd_measure::observer::LikeNeighbours;
use std::collections::BTreeMap;

/// The like and all neighbours within r_c of each type's particles, per sample.
pub struct LikeSeries {
    counter: LikeNeighbours,
    /// Sums over the samples so far (the counter's), to take each sample's counts from.
    last: (Vec<u64>, Vec<u64>),
    /// `like[t][s]`, `all[t][s]`: type t at sample s.
    like: Vec<Vec<f64>>,
    all: Vec<Vec<f64>>,
    names: Vec<String>,
}

impl LikeSeries {
    pub fn new(names: Vec<String>) -> LikeSeries {
        let types = names.len();
        LikeSeries {
            counter: LikeNeighbours::new(names.clone()),
            last: (vec![0; types], vec![0; types]),
            like: vec![Vec::new(); types],
            all: vec![Vec::new(); types],
            names,
        }
    }

    pub fn record(&mut self, sys: &System) {
        self.counter.record(sys);
        let (like, all) = self.counter.sums();
        for t in 0..self.names.len() {
            self.like[t].push((like[t] - self.last.0[t]) as f64);
            self.all[t].push((all[t] - self.last.1[t]) as f64);
        }
        self.last = (like.to_vec(), all.to_vec());
    }

    /// Per type name, the fraction of like neighbours over all samples with its standard error
    /// (the ratio of the blocks' sums); None for a type without neighbours.
    pub fn fractions(&self, blocks: usize) -> BTreeMap<String, Option<Estimate>> {
        let each = self.like.iter().zip(&self.all);
        let f = each.map(|(l, a)| (a.iter().sum::<f64>() > 0.0).then(|| ratio(l, a, blocks)));
        self.names.iter().cloned().zip(f).collect()
    }
}

/// The mean bond length, <R_ee^2> and <R_g^2> of the linear chains (see
/// [`dpd_measure::chains::linear_chains`], unwrapped by minimum-image bond vectors), per sample.
pub struct ChainSeries {
    bonds: Vec<(u32, u32)>,
    chains: Vec<Chain>,
    /// Scratch: the storage index of each id.
    at: Vec<u32>,
    pub bond_length: Vec<f64>,
    pub end_to_end: Vec<f64>,
    pub gyration: Vec<f64>,
}

impl ChainSeries {
    /// The series of `sys`'s bonds, None without bonds.
    pub fn new(sys: &System) -> Option<ChainSeries> {
        let topology = sys.topology().filter(|t| !t.bonds().is_empty())?;
        let bonds: Vec<(u32, u32)> = topology.bonds().iter().map(|b| (b.i, b.j)).collect();
        Some(ChainSeries {
            chains: linear_chains(sys.len(), &bonds),
            bonds,
            at: vec![0; sys.len()],
            bond_length: Vec::new(),
            end_to_end: Vec::new(),
            gyration: Vec::new(),
        })
    }

    pub fn record(&mut self, sys: &System) {
        for (k, &id) in sys.ids().iter().enumerate() {
            self.at[id as usize] = k as u32;
        }
        let (q, bx, at) = (sys.positions(), sys.boundary(), &self.at);
        let x = |id: u32| q[at[id as usize] as usize];
        let length = |&(i, j): &(u32, u32)| bx.min_image(x(j) - x(i)).norm();
        let mean = |v: Vec<f64>| v.iter().sum::<f64>() / v.len() as f64;
        self.bond_length
            .push(mean(self.bonds.iter().map(length).collect()));
        if !self.chains.is_empty() {
            let u: Vec<_> = self.chains.iter().map(|c| unwrapped(c, x, bx)).collect();
            self.end_to_end
                .push(mean(u.iter().map(|c| end_to_end_squared(c)).collect()));
            self.gyration
                .push(mean(u.iter().map(|c| gyration_squared(c)).collect()));
        }
    }
}
