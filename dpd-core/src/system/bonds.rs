//! The bonded-force cache: evaluated at most once per set of positions, and only for a system
//! with a topology.

use super::System;
use crate::bonded::{BondedSums, Frame, Overstretch};
use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::error::ParamError;
use crate::stamp::Stamp;
use crate::{Tensor, Vec3};

impl System {
    /// Whether the system has bonded forces: a topology with some bond or angle.
    pub(crate) fn has_bonded_forces(&self) -> bool {
        self.bonded
            .as_ref()
            .is_some_and(|b| !b.topology().is_empty())
    }

    fn frame(&self) -> Frame<'_> {
        frame(&self.q, &self.bx, self.shear.as_ref())
    }

    /// The momenta and the bonded forces at the current positions (evaluated if needed), or
    /// `None` without a topology.
    pub(crate) fn momenta_and_bonded(&mut self) -> Option<(&mut [Vec3], &[Vec3])> {
        let located = self.bonded.as_ref()?;
        if !self.bonded_at.is_fresh(self.positions) {
            let frame = frame(&self.q, &self.bx, self.shear.as_ref());
            let found = located.forces(frame, &mut self.bonded_forces);
            self.overstretch = self.overstretch.or(found);
            self.bonded_at = Stamp::at(self.positions);
            self.counters.bonded_force_evaluations += 1;
        }
        Some((&mut self.p, &self.bonded_forces))
    }

    /// The bonded potential energy at the current positions (0 without a topology; NaN with a
    /// FENE bond at or beyond `R0`).
    pub fn bonded_energy(&self) -> f64 {
        self.bonded_sums().energy
    }

    /// The bonded energy, Laplacian and virial at the current positions (zeros without a
    /// topology).
    pub(crate) fn bonded_sums(&self) -> BondedSums {
        self.bonded
            .as_ref()
            .map_or_else(BondedSums::default, |located| located.sums(self.frame()))
    }

    /// The bonded virial tensor at the current positions (zero without a topology).
    pub(crate) fn bonded_virial_tensor(&self) -> Tensor {
        self.bonded
            .as_ref()
            .map_or_else(Tensor::zeros, |located| located.virial_tensor(self.frame()))
    }

    /// The bonded forces at the current positions, evaluated afresh and not cached (for
    /// observables, which may run on a scratch copy), or `None` without a topology.
    pub(crate) fn bonded_forces_now(&self) -> Option<Vec<Vec3>> {
        let located = self.bonded.as_ref()?;
        let mut forces = Vec::new();
        located.forces(self.frame(), &mut forces);
        Some(forces)
    }

    /// Why a step that found a bond overstretched is a blow-up, naming the bond and its ids.
    pub(crate) fn overstretch_reason(&self, o: Overstretch) -> String {
        let topology = self
            .topology()
            .expect("only a bonded system finds an overstretch");
        let bond = topology.bonds()[o.bond];
        format!(
            "bond {} between particles {} and {} reached length {:.6}, at or beyond the reach \
             of its style {}",
            o.bond,
            bond.i,
            bond.j,
            o.r,
            topology.bond_types()[bond.kind as usize]
        )
    }

    /// What a blow-up that no bond beyond its reach explains adds, read before the step is
    /// undone: the particle on which the step's last bonded evaluation put the largest force,
    /// and its bonds (a FENE bond's force grows without bound toward `R0` and can fling a bead
    /// across the box within one drift, where no evaluation sees the bond past `R0`); ""
    /// without bonds.
    pub(crate) fn largest_bonded_force_note(&self) -> String {
        let Some(topology) = self.topology().filter(|t| !t.bonds().is_empty()) else {
            return String::new();
        };
        let forces = self.bonded_forces.iter().map(|f| f.norm()).enumerate();
        let Some((k, largest)) = forces.max_by(|a, b| a.1.total_cmp(&b.1)) else {
            return String::new();
        };
        let id = self.id[k];
        let bonds: Vec<String> = (topology.bonds().iter().enumerate())
            .filter(|(_, b)| b.i == id || b.j == id)
            .map(|(n, b)| {
                let style = topology.bond_types()[b.kind as usize];
                format!("bond {n} between particles {} and {} ({style})", b.i, b.j)
            })
            .collect();
        format!(
            "; the step's last bonded evaluation put its largest force, {largest:.3e}, on \
             particle {id}, of {}",
            bonds.join(", ")
        )
    }

    /// Refuse a start with a bond beyond its reach (a FENE bond at or beyond `R0`).
    pub(crate) fn check_bond_lengths(&self) -> Result<(), ParamError> {
        let Some(located) = &self.bonded else {
            return Ok(());
        };
        match located.overstretch(self.frame()) {
            None => Ok(()),
            Some(o) => {
                let bond = located.topology().bonds()[o.bond];
                Err(ParamError::new(
                    format!("bonds[{}]", o.bond),
                    format!("ids {}, {} at distance {}", bond.i, bond.j, o.r),
                    "a FENE bond must start shorter than its R0",
                ))
            }
        }
    }
}

fn frame<'a>(q: &'a [Vec3], bx: &'a PeriodicBox, shear: Option<&'a LeesEdwards>) -> Frame<'a> {
    Frame { q, bx, shear }
}
