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

/// A topology with its bonds and angles in storage indices, ordered so that the force loops
/// walk the particles' storage forward: the bonds by the storage index of their first particle
/// `i`, the angles by that of their vertex `j` (ties in the topology's order). Since the
/// particles are stored in cell order, the other particles of a bond or an angle are stored
/// near it too.
#[derive(Clone, Debug)]
pub(crate) struct Located {
    topology: Topology,
    bonds: Vec<Bond>,
    /// The topology's index of each of `bonds` (to name a bond in messages).
    bond_index: Vec<u32>,
    angles: Vec<Angle>,
    /// Where each bond goes: by the storage index of its first particle.
    bond_slots: Slots,
    /// Where each angle goes: by the storage index of its vertex.
    angle_slots: Slots,
    /// Scratch: the storage index of each id ([`Located::locate`]) or of each former storage
    /// index ([`Located::permute`]).
    at: Vec<u32>,
    /// Scratch of [`Located::permute`]: the former slot of each slot.
    from: Vec<u32>,
}

impl Located {
    /// `topology` for particles stored in the order of `ids` (a permutation of its ids).
    pub(crate) fn new(topology: Topology, ids: &[u32]) -> Located {
        let n = topology.particles();
        let mut located = Located {
            bonds: topology.bonds().to_vec(),
            bond_index: vec![0; topology.bonds().len()],
            angles: topology.angles().to_vec(),
            bond_slots: Slots::new(n, topology.bonds().iter().map(|b| b.i)),
            angle_slots: Slots::new(n, topology.angles().iter().map(|a| a.j)),
            topology,
            at: Vec::new(),
            from: Vec::new(),
        };
        located.locate(ids);
        located
    }

    /// Re-express and re-order the bonds and angles for particles now stored in the order of
    /// `ids` (counting sorts by storage index: linear in the particles and bonds).
    pub(crate) fn locate(&mut self, ids: &[u32]) {
        self.at.resize(ids.len(), 0);
        for (k, &id) in ids.iter().enumerate() {
            self.at[id as usize] = k as u32;
        }
        let at = &self.at;
        self.bond_slots.start(ids);
        for (n, b) in self.topology.bonds().iter().enumerate() {
            let i = at[b.i as usize];
            let slot = self.bond_slots.take(i);
            self.bonds[slot] = Bond {
                i,
                j: at[b.j as usize],
                kind: b.kind,
            };
            self.bond_index[slot] = n as u32;
        }
        self.angle_slots.start(ids);
        for a in self.topology.angles() {
            let j = at[a.j as usize];
            self.angles[self.angle_slots.take(j)] = Angle {
                i: at[a.i as usize],
                j,
                k: at[a.k as usize],
                kind: a.kind,
            };
        }
    }

    /// Follow the particles through the re-sort `v[k] <- v[order[k]]`: the result of
    /// [`Located::locate`] with the re-sorted ids, bond for bond and angle for angle, derived
    /// from the located lists themselves. Their reads follow the storage order, which a re-sort
    /// into cells changes little, where `locate`'s go by id, all over the storage (a melt of
    /// N = 24 000: 4 % of an ABOBA step's time in `locate`, perf).
    pub(crate) fn permute(&mut self, order: &[u32]) {
        self.at.resize(order.len(), 0);
        for (k, &old) in order.iter().enumerate() {
            self.at[old as usize] = k as u32;
        }
        let at = |k: u32| self.at[k as usize];
        self.bond_slots.follow(order, &mut self.from);
        self.bonds = gather(&self.from, &self.bonds, |b| Bond {
            i: at(b.i),
            j: at(b.j),
            ..b
        });
        self.bond_index = gather(&self.from, &self.bond_index, |n| n);
        self.angle_slots.follow(order, &mut self.from);
        self.angles = gather(&self.from, &self.angles, |a| Angle {
            i: at(a.i),
            j: at(a.j),
            k: at(a.k),
            ..a
        });
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

/// `items` in the slot order `from` (`from[s]` the former slot of the item now in slot `s`),
/// each mapped by `f`.
fn gather<T: Copy>(from: &[u32], items: &[T], f: impl Fn(T) -> T) -> Vec<T> {
    from.iter().map(|&s| f(items[s as usize])).collect()
}

/// A counting sort by storage index of a list whose items each name one particle by id.
#[derive(Clone, Debug)]
struct Slots {
    /// How many items name each id (empty for an empty list).
    per_id: Vec<u32>,
    /// The next free slot of each storage index.
    next: Vec<u32>,
}

impl Slots {
    /// For the items naming `ids` (each below `particles`).
    fn new(particles: usize, ids: impl ExactSizeIterator<Item = u32>) -> Slots {
        let mut per_id = vec![0; if ids.len() == 0 { 0 } else { particles }];
        for id in ids {
            per_id[id as usize] += 1;
        }
        Slots {
            per_id,
            next: Vec::new(),
        }
    }

    /// Start a sort for particles stored in the order of `ids`: the items of the particle at
    /// storage index `k` go after those of the particles before it.
    fn start(&mut self, ids: &[u32]) {
        if self.per_id.is_empty() {
            return;
        }
        self.next.resize(ids.len(), 0);
        let mut slot = 0;
        for (next, &id) in self.next.iter_mut().zip(ids) {
            *next = slot;
            slot += self.per_id[id as usize];
        }
    }

    /// Follow the re-sort `v[k] <- v[order[k]]` of the particles after a sort ([`Slots::start`]
    /// and a [`Slots::take`] for every item): `from[s]` becomes the former slot of the item
    /// that goes into slot `s`, each particle's items keep their order, and the slots end as a
    /// sort in the new order would leave them.
    fn follow(&mut self, order: &[u32], from: &mut Vec<u32>) {
        from.clear();
        if self.per_id.is_empty() {
            return;
        }
        // After a sort `next[k]` is the end of the slots of the particle at `k`.
        let end = &self.next;
        from.resize(end.last().map_or(0, |&n| n as usize), 0);
        let mut ends = vec![0; order.len()];
        let mut slot = 0;
        for (k, &old) in order.iter().enumerate() {
            let old = old as usize;
            let start = if old == 0 { 0 } else { end[old - 1] };
            for s in start..end[old] {
                from[slot] = s;
                slot += 1;
            }
            ends[k] = slot as u32;
        }
        self.next = ends;
    }

    /// The slot of the next item of the particle at storage index `k`.
    #[inline]
    fn take(&mut self, k: u32) -> usize {
        let next = &mut self.next[k as usize];
        *next += 1;
        *next as usize - 1
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
    /// particles whose ids the topology names, every bond and angle once, the bonds in the
    /// storage order of their first particle and the angles in that of their vertex.
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
        let mut seen = vec![false; topology.bonds().len()];
        for (l, &n) in located.bonds().iter().zip(&located.bond_index) {
            let b = topology.bonds()[n as usize];
            assert_eq!(
                (ids[l.i as usize], ids[l.j as usize], l.kind),
                (b.i, b.j, b.kind)
            );
            assert!(
                !std::mem::replace(&mut seen[n as usize], true),
                "bond {n} twice"
            );
        }
        assert!(seen.iter().all(|&s| s), "every bond located");
        assert!(located.bonds().is_sorted_by_key(|b| b.i));
        let by_ids = |a: &Angle| (ids[a.i as usize], ids[a.j as usize], ids[a.k as usize]);
        let mut found: Vec<_> = located.angles().iter().map(by_ids).collect();
        let mut named: Vec<_> = topology.angles().iter().map(|a| (a.i, a.j, a.k)).collect();
        found.sort_unstable();
        named.sort_unstable();
        assert_eq!(found, named);
        assert!(located.angles().is_sorted_by_key(|a| a.j));
    }

    /// Following a series of random re-sorts with `permute` gives, bond for bond, angle for
    /// angle and slot for slot, what `locate` gives with the re-sorted ids, also where a
    /// particle is the first of several bonds (kept in the topology's order) or of none.
    #[test]
    fn permuting_is_locating_by_the_new_ids() {
        use rand::seq::SliceRandom;
        use rand::SeedableRng;
        let chains = chains(400);
        let mut bonds = chains.bonds().to_vec();
        bonds.extend((0..390).step_by(7).map(|i| Bond {
            i,
            j: i + 5,
            kind: 0,
        }));
        let topology = TopologyBuilder {
            particles: 400,
            bond_types: chains.bond_types().to_vec(),
            bonds,
            angle_types: chains.angle_types().to_vec(),
            angles: chains.angles().to_vec(),
        }
        .build()
        .unwrap();
        let mut rng = rand_chacha::ChaCha12Rng::seed_from_u64(3);
        let mut ids: Vec<u32> = (0..400).collect();
        ids.shuffle(&mut rng);
        let mut located = Located::new(topology.clone(), &ids);
        for _ in 0..5 {
            let mut order: Vec<u32> = (0..400).collect();
            order.shuffle(&mut rng);
            ids = order.iter().map(|&k| ids[k as usize]).collect();
            located.permute(&order);
            let want = Located::new(topology.clone(), &ids);
            assert_eq!(located.bonds, want.bonds);
            assert_eq!(located.bond_index, want.bond_index);
            assert_eq!(located.angles, want.angles);
            assert_eq!(located.bond_slots.next, want.bond_slots.next);
            assert_eq!(located.angle_slots.next, want.angle_slots.next);
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
