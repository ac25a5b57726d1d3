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

    /// What a blow-up that no bond beyond its reach explains adds: the bond nearest its reach
    /// at the current positions (a FENE bond's force grows without bound toward `R0`, and can
    /// fling a bead across the box within one drift, where no evaluation sees the bond past
    /// `R0`); "" without bonds that have a reach.
    pub(crate) fn nearest_reach_note(&self) -> String {
        let Some(located) = &self.bonded else {
            return String::new();
        };
        located
            .nearest_reach(self.frame())
            .map_or_else(String::new, |o| {
                let topology = located.topology();
                let bond = topology.bonds()[o.bond];
                format!(
                "; the bond nearest its reach at the step's start: bond {} between particles {} \
                 and {}, length {:.6}, of style {}",
                o.bond,
                bond.i,
                bond.j,
                o.r,
                topology.bond_types()[bond.kind as usize]
            )
            })
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
