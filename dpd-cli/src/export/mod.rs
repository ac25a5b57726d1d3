//! Generators of sources that run the workspace's schemes in other engines.

pub mod lammps;
