//! The Verlet list with a skin (see the module docs of [`super`]).

use super::{CellGrid, Hits, Runs};
use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::chunked::Parts;
use crate::Vec3;

/// Verlet list with a skin, in sweep order, rebuilt on displacement.
///
/// A build has two halves: [`VerletList::bin`] bins the positions and returns the cell order,
/// the owner puts its particles in that order, then [`VerletList::build`] scans them. With skin
/// 0 the list keeps no candidates: the owner takes the pairs straight from
/// [`VerletList::grid`]'s sweep.
#[derive(Clone, Debug)]
pub struct VerletList {
    skin: f64,
    reference: Vec<Vec3>,
    /// The sliding boundary at the last build (its offset fixed the sweep order).
    shear: Option<LeesEdwards>,
    candidates: Parts<(u32, u32)>,
    groups: Runs,
    grid: CellGrid,
    /// Whether a build matches the positions (with skin 0 cleared by
    /// [`VerletList::positions_changed`]; with a skin the displacement test decides).
    built: bool,
    builds: u64,
}

impl VerletList {
    /// An empty list with the given skin (length units, >= 0).
    pub fn new(skin: f64) -> Self {
        VerletList {
            skin,
            reference: Vec::new(),
            shear: None,
            candidates: Parts::default(),
            groups: Runs::default(),
            grid: CellGrid::default(),
            built: false,
            builds: 0,
        }
    }

    pub fn skin(&self) -> f64 {
        self.skin
    }

    /// Number of builds so far.
    pub fn builds(&self) -> u64 {
        self.builds
    }

    /// Positions of the last build (empty before the first, and always with skin 0).
    pub fn reference(&self) -> &[Vec3] {
        &self.reference
    }

    /// The sliding boundary at the last build (`None` before the first or without shear).
    pub fn reference_shear(&self) -> Option<&LeesEdwards> {
        self.shear.as_ref()
    }

    /// The grid of the last build.
    pub fn grid(&self) -> &CellGrid {
        &self.grid
    }

    /// First half of a build: bin `q` for cutoff `rc` and return the cell order (see
    /// [`CellGrid::bin`]).
    pub fn bin(&mut self, q: &[Vec3], bx: &PeriodicBox, rc: f64) -> &[u32] {
        self.grid.bin(q, bx, rc + self.skin)
    }

    /// Second half of a build, after [`VerletList::bin`]: `q` are the positions in the cell
    /// order it returned. Candidate indices are indices into `q`.
    pub fn build(&mut self, q: &[Vec3], bx: &PeriodicBox, shear: Option<&LeesEdwards>, rc: f64) {
        if self.skin > 0.0 {
            let push = |h: &Hits, out: &mut Vec<(u32, u32)>| {
                out.extend(h.b[..h.len()].iter().map(|&b| (h.a, b)))
            };
            let reach = rc + self.skin;
            self.groups = self
                .grid
                .sweep(q, bx, shear, reach, &mut self.candidates, push, |_| {});
            self.reference.clear();
            self.reference.extend_from_slice(q);
        }
        self.shear = shear.copied();
        self.built = true;
        self.builds += 1;
    }

    /// The positions moved: with skin 0 the list is stale.
    pub fn positions_changed(&mut self) {
        if self.skin == 0.0 {
            self.built = false;
        }
    }

    /// Forget the build (the particle order it refers to is gone).
    pub fn invalidate(&mut self) {
        self.built = false;
    }

    /// Whether the list must be rebuilt for positions `q`.
    pub fn needs_rebuild(&self, q: &[Vec3], bx: &PeriodicBox, shear: Option<&LeesEdwards>) -> bool {
        if !self.built {
            return true;
        }
        if self.skin == 0.0 {
            return shear.map(LeesEdwards::offset) != self.shear.as_ref().map(LeesEdwards::offset);
        }
        if q.len() != self.reference.len() {
            return true;
        }
        match (shear, &self.shear) {
            (None, None) => self.moved_too_far(q, self.skin, |d| bx.min_image(d)),
            (Some(now), Some(then)) => {
                let reach = self.skin - 3.0 * (now.travel() - then.travel()).abs();
                reach < 0.0 || self.moved_too_far(q, reach, |d| now.min_image(bx, d).0)
            }
            _ => true,
        }
    }

    /// Whether a particle moved more than `reach / 2` since the last build, displacements
    /// measured by `image`.
    fn moved_too_far(&self, q: &[Vec3], reach: f64, image: impl Fn(Vec3) -> Vec3) -> bool {
        let limit = 0.25 * reach * reach;
        q.iter().zip(&self.reference).any(|(a, b)| {
            let d2 = image(a - b).norm_squared();
            d2 > limit || d2.is_nan()
        })
    }

    /// Candidate pairs within `r_c + skin` at the last build, in sweep order (none with skin 0).
    pub fn candidates(&self) -> &Parts<(u32, u32)> {
        &self.candidates
    }

    /// Grouping of [`VerletList::candidates`] into runs and colours.
    pub fn groups(&self) -> &Runs {
        &self.groups
    }
}
