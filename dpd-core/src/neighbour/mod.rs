//! Neighbour search in O(N): a cell grid, and a Verlet list with a skin built from it.
//!
//! # Particle order
//!
//! The grid bins particles into cells and returns the cell order (a stable counting sort). A
//! [`crate::System`] stores its particles in that order, re-sorted at every list build, so that
//! the particles of a cell and of a row of cells along z are contiguous in memory: the cell
//! scan reads positions sequentially and the pair loops touch nearby memory. Particles keep
//! their identity through [`crate::System::ids`].
//!
//! # Sweep order
//!
//! The Verlet list fixes the order in which every pairwise sub-flow visits the pairs. Cells of
//! edge at least `r_c + skin` own the pairs between themselves and 13 of their neighbours (a
//! half stencil spanning offsets `[0, 1] x [-1, 1] x [-1, 1]`). The cells are grouped into
//! units that one thread sweeps in turn: a unit is a layer of cells `cx` (all `cy`, all `cz`),
//! or, when a layer has at least 16 cells along y, a block of four to seven consecutive `cy`
//! of a layer (an even number of blocks, all `cz`). A unit's cells are consecutive cell
//! indices, so its particles are one range of memory. Units are coloured by
//! `(cx mod m_x) m_y + b mod m_y`, `b` the block index, with `m_x` the smallest divisor from 2
//! to 5 of the layer count (which is rounded down by at most two layers to have one) and
//! `m_y = 2` (1 with whole layers). The half stencil reaches one layer along x and one cell to
//! either side along y, so two units of one colour, at least two layers apart or separated by
//! a block of at least two cells, touch disjoint particles and can be processed concurrently.
//! The order is: colours in order, within a colour units by ascending `(cx, b)`, within a unit
//! cells by ascending index, within a cell the pairs in scan order: particle by particle `a`
//! of the cell in cell order, its pairs with the later particles `b > a` of the cell, then
//! with the stencil: the cell above along z, then the rows `(dx, dy) = (0, 1), (1, -1),
//! (1, 0), (1, 1)`, each row its cells `dz = -1, 0, 1` in storage order. (The cell and its
//! stencil are copied once per cell and tested in vectorised blocks, see `stencil.rs`. Pairs
//! that share a particle are in the same relative order as when all pairs within the cell come
//! first and the stencil is then scanned range by range for all particles of the cell, so these
//! orders give the same results.)
//! Within a colour, units commute, so this order gives the same result on any number of
//! threads. A sweep in units keeps the particles it touches close together: consecutive cells
//! share most of their stencils, and a colour reads each particle at most about once, so a
//! pass reads the particle arrays a few times (two to four colours) where a colouring of
//! single cells (18 to 125 colours) read most of them once per colour.
//! Where the box is too small for the grid (fewer than 3 cells along some axis) there is one
//! cell and one colour, and processing is sequential.
//!
//! The order is a function of the positions at the last build; a checkpoint stores those
//! positions so that a restarted run rebuilds the same list. The list is rebuilt when a particle
//! has moved more than `skin / 2` since the last build; with skin 0 it is rebuilt whenever
//! the positions changed, and keeps neither candidates nor reference positions.
//!
//! # Lees-Edwards
//!
//! Under a sliding boundary ([`LeesEdwards`]) with a non-zero offset, the cells across the y
//! boundary are misaligned along x. Then the cells of the top row (`cy = n_y - 1`) own all
//! pairs with the images of the bottom row: for each `dz` the four image cells that overlap the
//! x-range `[cx - 1, cx + 2)` cell widths, scanned in order of increasing x. The bottom row
//! drops its stencil rows that cross downwards. Two top-row cells of one colour may
//! reach the same bottom cell, so these crossing runs form an extra colour after the others,
//! visited sequentially (`Runs::colours` then has one more group than the grid has colours). Everything else keeps the periodic order;
//! with offset 0 (in particular shear rate 0) the list is exactly the periodic one. Positions
//! that crossed the y boundary since the build carry the offset of their crossing, so the
//! rebuild test allows for the distance `travel` the images slid since the build: it rebuilds
//! when a particle moved more than `(skin - 3 travel) / 2` (one travel for the displacement of
//! each particle of a pair, one for the slide between them).

mod grid;
mod scan;
mod sliding;
mod stencil;
mod verlet;

pub use scan::Runs;
pub use stencil::Hits;
pub use verlet::VerletList;

/// Particles binned into cells of edge at least `min_cell`, and the sweep over their pairs.
#[derive(Clone, Debug, Default)]
pub struct CellGrid {
    dims: [usize; 3],
    /// Colour moduli of the layer index `cx` and of the y-block index (see the module docs);
    /// all 1 when not coloured.
    moduli: [usize; 2],
    /// Blocks each layer is split into along y (1: a unit is a whole layer).
    y_blocks: usize,
    coloured: bool,
    /// `cell_start[c]..cell_start[c + 1]`: cell-order indices of the particles of cell `c`.
    cell_start: Vec<u32>,
    /// `order[k]`: input index of the k-th particle in cell order.
    order: Vec<u32>,
    /// Cells in sweep order (colour by colour, unit by unit); `units[u]..units[u + 1]` are the
    /// positions in `sweep` of the cells of unit `u`, `colour_units[c]..colour_units[c + 1]`
    /// the units of colour `c`. They depend on `dims` only and are kept between builds.
    sweep: Vec<u32>,
    units: Vec<u32>,
    colour_units: Vec<u32>,
}

#[cfg(test)]
mod tests;
