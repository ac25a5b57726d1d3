//! What a checkpoint ([`crate::checkpoint`]) stores beyond the particles and settings that
//! build a system: the state a step depends on that only stepping sets.

use super::System;
use crate::boundary::LeesEdwards;
use crate::error::ParamError;
use crate::stamp::Stamp;
use crate::Vec3;

/// The state of a system that building one from its particles does not set.
pub(crate) struct Continuation {
    /// Number of completed steps.
    pub(crate) step: u64,
    /// The Lees-Edwards boundaries with their offset.
    pub(crate) shear: Option<LeesEdwards>,
    /// Largest drift summed since the neighbour list last checked the positions.
    pub(crate) travel: f64,
    /// The positions of the last neighbour-list build, in storage order, and the Lees-Edwards
    /// boundaries then (empty before the first build): the sweep order and the next rebuild
    /// depend on them.
    pub(crate) list_reference: Vec<Vec3>,
    pub(crate) list_shear: Option<LeesEdwards>,
    /// The full forces (with their noise) when they are valid at the current positions: what
    /// velocity Verlet carries into its next step.
    pub(crate) full_forces: Option<Vec<Vec3>>,
    /// The accept/reject tests of Metropolis-adjusted parts so far.
    pub(crate) acceptance: super::Acceptance,
}

impl System {
    /// This system's [`Continuation`].
    pub(crate) fn continuation(&self) -> Continuation {
        Continuation {
            step: self.step,
            shear: self.shear,
            travel: self.travel,
            list_reference: self.list.reference().to_vec(),
            list_shear: self.list.reference_shear().copied(),
            full_forces: self
                .full_at
                .is_fresh(self.positions)
                .then(|| self.full.clone()),
            acceptance: self.acceptance,
        }
    }

    /// Continue from `c` a system just built from the particles of a checkpoint, in the
    /// storage order of its last neighbour-list build. Errors name the field of `c` that does
    /// not fit the particles.
    pub(crate) fn resume(&mut self, c: Continuation) -> Result<(), ParamError> {
        // The saved positions are inside the box, so the builder moved no particle across the
        // sliding boundary; the saved offset is restored as it was.
        self.shear = c.shear;
        self.step = c.step;
        self.travel = c.travel;
        self.acceptance = c.acceptance;
        if !c.list_reference.is_empty() {
            if c.list_reference.len() != self.len() {
                return Err(ParamError::new(
                    "list_reference",
                    format!("{} entries", c.list_reference.len()),
                    format!("must have {} entries", self.len()),
                ));
            }
            // The reference positions were stored in cell order, so binning them again gives
            // the identity order and the particles stay where the checkpoint put them.
            let rc = self.params.rc();
            let reference = &c.list_reference;
            let order = self.list.bin(reference, &self.bx, rc);
            if order.iter().enumerate().any(|(k, &i)| i as usize != k) {
                return Err(ParamError::new(
                    "list_reference",
                    "positions not in the cell order of the neighbour grid",
                    "the positions of the last list build, in storage order, as written by save_checkpoint",
                ));
            }
            self.list
                .build(reference, &self.bx, c.list_shear.as_ref(), rc);
        }
        if let Some(full) = c.full_forces {
            if full.len() != self.len() {
                return Err(ParamError::new(
                    "full_forces",
                    format!("{} entries", full.len()),
                    format!("must have {} entries", self.len()),
                ));
            }
            self.full = full;
            self.full_at = Stamp::at(self.positions);
        }
        Ok(())
    }
}
