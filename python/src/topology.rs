//! What a simulation's particles are, by particle id: their types and masses, the bonds and
//! angles between them with their types' names, and the linear chains the bonds make.

use dpd_core::bonded::Topology;
use dpd_core::System;
use dpd_measure::chains::linear_chains;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;

/// `values` (in storage order) in the order of the particles' ids.
pub fn by_id<T: Copy + Default>(sys: &System, values: &[T]) -> Vec<T> {
    let mut out = vec![T::default(); values.len()];
    for (&v, &id) in values.iter().zip(sys.ids()) {
        out[id as usize] = v;
    }
    out
}

/// The type of each particle, by id.
pub fn typeid<'py>(py: Python<'py>, sys: &System) -> Bound<'py, PyArray1<i64>> {
    let kinds: Vec<i64> = sys.kinds().iter().map(|&t| i64::from(t)).collect();
    by_id(sys, &kinds).into_pyarray(py)
}

/// `rows` of `width` ids as a (rows, width) array.
fn id_rows<'py, const W: usize>(py: Python<'py>, rows: Vec<[u32; W]>) -> Bound<'py, PyArray2<i64>> {
    let n = rows.len();
    let flat: Vec<i64> = rows.into_iter().flatten().map(i64::from).collect();
    Array2::from_shape_vec((n, W), flat)
        .expect("n rows of W")
        .into_pyarray(py)
}

/// The bonds `(i, j)` of `sys` by id, (0, 2) without bonds.
pub fn bonds<'py>(py: Python<'py>, sys: &System) -> Bound<'py, PyArray2<i64>> {
    let b = sys.topology().map_or(&[][..], Topology::bonds);
    id_rows(py, b.iter().map(|b| [b.i, b.j]).collect())
}

/// The angles `(i, j, k)` of `sys` by id, `j` the vertex; (0, 3) without angles.
pub fn angles<'py>(py: Python<'py>, sys: &System) -> Bound<'py, PyArray2<i64>> {
    let a = sys.topology().map_or(&[][..], Topology::angles);
    id_rows(py, a.iter().map(|a| [a.i, a.j, a.k]).collect())
}

/// The type of each bond (`angles` false) or angle (true), in the order of `bonds`/`angles`.
pub fn bonded_typeid<'py>(
    py: Python<'py>,
    sys: &System,
    angles: bool,
) -> Bound<'py, PyArray1<i64>> {
    let kinds: Vec<i64> = match (sys.topology(), angles) {
        (None, _) => Vec::new(),
        (Some(t), false) => t.bonds().iter().map(|b| i64::from(b.kind)).collect(),
        (Some(t), true) => t.angles().iter().map(|a| i64::from(a.kind)).collect(),
    };
    kinds.into_pyarray(py)
}

/// The linear chains of `sys`'s bonds (molecules whose bonds make one open, unbranched path),
/// each the ids of its beads in order from its end with the smaller id.
pub fn chains<'py>(py: Python<'py>, sys: &System) -> Vec<Bound<'py, PyArray1<i64>>> {
    let b = sys.topology().map_or(&[][..], Topology::bonds);
    let pairs: Vec<(u32, u32)> = b.iter().map(|b| (b.i, b.j)).collect();
    let chains = linear_chains(sys.len(), &pairs);
    let ids = |c: Vec<u32>| c.into_iter().map(i64::from).collect::<Vec<_>>();
    chains
        .into_iter()
        .map(|c| ids(c).into_pyarray(py))
        .collect()
}
