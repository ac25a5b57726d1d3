//! Observers of a run: each samples the system at the steps it asks for and finishes into the
//! run's [`RunResult`]. The runner (`crate::runner`) owns the loop; an observer owns one
//! measurement, in one file:
//!
//! | file | measures | switched on by |
//! |---|---|---|
//! | `thermo.rs` | T_K, T_C, U, P over the window (`processing`: at processed positions) | always |
//! | `rdf.rs` | g(r) | `[rdf]` |
//! | `pair_rdf.rs` | g(r) of each pair of species | `[rdf]` with `[[species]]` |
//! | `neighbours.rs` | the fraction of like neighbours of each species | `like_neighbours` |
//! | `chains.rs` | bond lengths, end-to-end distance and radius of gyration of chains | bonds |
//! | `vacf.rs` | the diffusion coefficient | `[vacf]` |
//! | `viscosity.rs` | the shear viscosity | a non-zero `shear_rate` |
//! | `profile.rs` | slab profiles | `[profile]` |
//! | `species_profile.rs` | slab densities of each species | `[profile]` with `[[species]]` |
//! | `trajectory.rs` | frames into a file | `[trajectory]` |
//! | `data_out.rs` | the last state into a LAMMPS data file | `write_data` |
//! | `energy.rs` | heat and shadow work | `energy_balance` |
//!
//! The interface, [`Observer`] and what it is given, is in `interface.rs`; `typed.rs` visits
//! the pairs of a state with their particles' types. To add an
//! observable: write its file with a type implementing [`Observer`] and a `new`
//! that returns `None` when the scene does not ask for it (its key belongs to a scene section,
//! usually `crate::scene::observe`), list `new` in [`for_run`], and give [`RunResult`] the
//! field its `finish` fills (`#[serde(default, skip_serializing_if = "Option::is_none")]`, so
//! that other runs' JSON does not change).
//!
//! A sample is taken at the end of a full step, every `Setup::every` steps and at the last
//! step, in the averaging window (the last `average_fraction` of the run); observers are
//! called in the order of [`for_run`].

mod chains;
mod data_out;
mod energy;
mod interface;
mod neighbours;
mod pair_rdf;
mod profile;
mod rdf;
mod species_profile;
mod thermo;
mod trajectory;
mod typed;
mod vacf;
mod viscosity;

pub use interface::{Boxed, End, Observer, Setup};
pub use neighbours::LikeNeighbours;
pub use pair_rdf::PairRdf;
pub use species_profile::SpeciesProfile;
pub use trajectory::{Recorder, TypeNames};

use dpd_core::{ParamError, System};

/// Makes an observer if the scene asks for it.
type Make = for<'a> fn(&Setup<'a>, &mut System) -> Result<Option<Boxed<'a>>, ParamError>;

/// The observers of a run, in the order they are called.
pub fn for_run<'a>(setup: &Setup<'a>, sys: &mut System) -> Result<Vec<Boxed<'a>>, ParamError> {
    const MAKE: [Make; 12] = [
        thermo::new,
        rdf::new,
        pair_rdf::new,
        neighbours::new,
        chains::new,
        vacf::new,
        viscosity::new,
        profile::new,
        species_profile::new,
        trajectory::new,
        data_out::new,
        energy::new,
    ];
    let mut observers = Vec::new();
    for make in MAKE {
        observers.extend(make(setup, sys)?);
    }
    Ok(observers)
}
