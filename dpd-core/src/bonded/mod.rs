//! Bonded interactions: bonds and angles between particles named by id.
//!
//! Conventions (LAMMPS's, so that a data file means the same system in both engines; see
//! docs/systems.md, "Bonds and angles"):
//! - [`BondStyle::Harmonic`]: `E = K (r - r0)^2`, no factor 1/2.
//! - [`BondStyle::Fene`]: `E = -K R0^2 / 2 ln(1 - (r/R0)^2)`, LAMMPS's `fene` with `epsilon =
//!   0`: DPD beads keep their soft repulsion, so the WCA core of Kremer-Grest chains is left
//!   out.
//! - [`AngleStyle::Cosine`]: `E = K (1 + cos theta)`; [`AngleStyle::CosineSquared`]: `E = K
//!   (cos theta - cos theta0)^2`, `theta` the angle at the vertex `j` of `i - j - k`.
//!
//! Lengths in the unit of the pair cut-off's, energies in k_B T's unit, under minimum image.
//! A [`Topology`] names particles by id; the system holds it with its bonds and angles also in
//! storage indices ([`Located`]), refreshed whenever the particles are re-sorted.

mod forces;
mod style;
mod topology;

pub(crate) use forces::{BondedSums, Frame, Overstretch};
pub use style::{AngleStyle, BondStyle};
pub use topology::{Angle, Bond, Topology, TopologyBuilder};

/// A topology with its bonds and angles in storage indices: the same lists as the topology's,
/// in the same order, each id replaced by where that particle is stored now.
#[derive(Clone, Debug)]
pub(crate) struct Located {
    topology: Topology,
    bonds: Vec<Bond>,
    angles: Vec<Angle>,
    /// Scratch: the storage index of each id.
    at: Vec<u32>,
}

impl Located {
    /// `topology` for particles stored in the order of `ids` (a permutation of its ids).
    pub(crate) fn new(topology: Topology, ids: &[u32]) -> Located {
        let mut located = Located {
            bonds: topology.bonds().to_vec(),
            angles: topology.angles().to_vec(),
            topology,
            at: Vec::new(),
        };
        located.locate(ids);
        located
    }

    /// Re-express the bonds and angles for particles now stored in the order of `ids`.
    pub(crate) fn locate(&mut self, ids: &[u32]) {
        self.at.resize(ids.len(), 0);
        for (k, &id) in ids.iter().enumerate() {
            self.at[id as usize] = k as u32;
        }
        let at = &self.at;
        for (dst, b) in self.bonds.iter_mut().zip(self.topology.bonds()) {
            (dst.i, dst.j) = (at[b.i as usize], at[b.j as usize]);
        }
        for (dst, a) in self.angles.iter_mut().zip(self.topology.angles()) {
            (dst.i, dst.j, dst.k) = (at[a.i as usize], at[a.j as usize], at[a.k as usize]);
        }
    }

    pub(crate) fn topology(&self) -> &Topology {
        &self.topology
    }
    /// The bonds in storage indices.
    #[cfg(test)]
    pub(crate) fn bonds(&self) -> &[Bond] {
        &self.bonds
    }
    /// The angles in storage indices.
    #[cfg(test)]
    pub(crate) fn angles(&self) -> &[Angle] {
        &self.angles
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::init::equilibrium_box;
    use crate::params::Params;

    /// Chains of 4 beads over consecutive ids, with an angle at each inner bead.
    pub(crate) fn chains(particles: usize) -> Topology {
        let ids = (0..particles as u32).collect::<Vec<_>>();
        let chains = ids.chunks_exact(4);
        TopologyBuilder {
            particles,
            bond_types: vec![BondStyle::Harmonic { k: 2.0, r0: 0.0 }],
            bonds: chains
                .clone()
                .flat_map(|c| {
                    c.windows(2).map(|w| Bond {
                        i: w[0],
                        j: w[1],
                        kind: 0,
                    })
                })
                .collect(),
            angle_types: vec![AngleStyle::Cosine { k: 1.0 }],
            angles: chains
                .flat_map(|c| {
                    c.windows(3).map(|w| Angle {
                        i: w[0],
                        j: w[1],
                        k: w[2],
                        kind: 0,
                    })
                })
                .collect(),
        }
        .build()
        .unwrap()
    }

    /// After the particles are re-sorted into cell order, each located bond and angle joins the
    /// particles whose ids the topology names.
    #[test]
    fn located_bonds_follow_the_particles_through_re_sorting() {
        let topology = chains(400);
        let mut sys = equilibrium_box(Params::builder().build().unwrap(), 400, 3.0, 5)
            .unwrap()
            .topology(topology.clone())
            .build()
            .unwrap();
        sys.pairs();
        let ids = sys.ids().to_vec();
        assert_ne!(
            ids,
            (0..400).collect::<Vec<u32>>(),
            "the particles were re-sorted"
        );
        let located = sys.located().unwrap();
        assert_eq!(located.topology(), &topology);
        for (l, b) in located.bonds().iter().zip(topology.bonds()) {
            assert_eq!(
                (ids[l.i as usize], ids[l.j as usize], l.kind),
                (b.i, b.j, b.kind)
            );
        }
        for (l, a) in located.angles().iter().zip(topology.angles()) {
            let found = (ids[l.i as usize], ids[l.j as usize], ids[l.k as usize]);
            assert_eq!(found, (a.i, a.j, a.k));
        }
    }

    #[test]
    fn the_topology_must_be_for_the_systems_particles() {
        let err = equilibrium_box(Params::builder().build().unwrap(), 400, 3.0, 5)
            .unwrap()
            .topology(chains(404))
            .build()
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "invalid topology = 404 particles: must be built for the system's 400 particles"
        );
    }
}
