//! The bonds and angles of a LAMMPS data file: `Bonds`, `Angles`, `Bond Coeffs` and `Angle
//! Coeffs` read into a [`Topology`] and written from one, in LAMMPS's conventions (the
//! section's comment names the style): `harmonic` `K r0` (E = K (r - r0)^2), `fene` `K R0
//! epsilon sigma` with epsilon 0 (the WCA core is not modelled: bonded DPD beads keep their
//! soft repulsion), `cosine` `K`, `cosine/squared` `K theta0` (degrees).

use dpd_core::bonded::{Angle, AngleStyle, Bond, BondStyle, Topology, TopologyBuilder};
use dpd_core::ParamError;
use dpd_trajectory::lammps_data::{self, Coeffs, DataFile};
use std::collections::BTreeMap;

/// The topology of `data` (`None` without bonds and angles), particles indexed in the order
/// of their atom ids as [`crate::data_file::frame_of`] takes them.
pub fn topology_of(data: &DataFile) -> Result<Option<Topology>, ParamError> {
    if data.bonds.is_empty() && data.angles.is_empty() {
        return Ok(None);
    }
    let mut ids: Vec<u64> = data.atoms.iter().map(|a| a.id).collect();
    ids.sort_unstable();
    let index: BTreeMap<u64, u32> = ids
        .iter()
        .enumerate()
        .map(|(k, &id)| (id, k as u32))
        .collect();
    let at = |id: &u64| index[id];
    let bond_types = styles(
        &data.bond_coeffs,
        data.bond_types,
        "Bond Coeffs",
        bond_style,
    )?;
    let angle_types = styles(
        &data.angle_coeffs,
        data.angle_types,
        "Angle Coeffs",
        angle_style,
    )?;
    let kind = |k: u32| (k - 1) as u16;
    let builder = TopologyBuilder {
        particles: ids.len(),
        bond_types,
        bonds: data
            .bonds
            .iter()
            .map(|b| Bond {
                i: at(&b.atoms[0]),
                j: at(&b.atoms[1]),
                kind: kind(b.kind),
            })
            .collect(),
        angle_types,
        angles: data
            .angles
            .iter()
            .map(|a| {
                let [i, j, k] = a.atoms.each_ref().map(at);
                Angle {
                    i,
                    j,
                    k,
                    kind: kind(a.kind),
                }
            })
            .collect(),
    };
    builder.build().map(Some).map_err(|e| {
        ParamError::new(
            "init",
            e.to_string(),
            "the file's bonds and angles must be valid",
        )
    })
}

/// The style of each of the `types` types of a coefficient section; the error names the
/// section and the type.
fn styles<S>(
    coeffs: &Coeffs<u32>,
    types: u32,
    section: &str,
    style: fn(&str, &[f64]) -> Result<S, String>,
) -> Result<Vec<S>, ParamError> {
    (1..=types)
        .map(|t| {
            let key = format!("init: {section} {t}");
            let c = coeffs.by_type.get(&t).ok_or_else(|| {
                ParamError::new(
                    &key,
                    "missing",
                    "every type of the file needs its coefficients",
                )
            })?;
            let name = coeffs.style.as_deref().ok_or_else(|| {
                let why = format!("needs its style as the section's comment: `{section} # ...`");
                ParamError::new(&key, "no style", why)
            })?;
            style(name, c).map_err(|why| ParamError::new(&key, format!("{name} {c:?}"), why))
        })
        .collect()
}

fn bond_style(name: &str, c: &[f64]) -> Result<BondStyle, String> {
    match (name, c) {
        ("harmonic", &[k, r0]) => Ok(BondStyle::Harmonic { k, r0 }),
        ("fene", &[k, r_max, 0.0, _]) => Ok(BondStyle::Fene { k, r_max }),
        ("fene", &[_, _, _, _]) => Err("must have epsilon 0: DPD beads keep their soft \
                                        repulsion instead of the WCA core"
            .into()),
        ("harmonic", _) => Err("must be `K r0`".into()),
        ("fene", _) => Err("must be `K R0 epsilon sigma`".into()),
        _ => Err("must be bond style harmonic or fene".into()),
    }
}

fn angle_style(name: &str, c: &[f64]) -> Result<AngleStyle, String> {
    match (name, c) {
        ("cosine", &[k]) => Ok(AngleStyle::Cosine { k }),
        ("cosine/squared", &[k, degrees]) => Ok(AngleStyle::CosineSquared {
            k,
            theta0: degrees.to_radians(),
        }),
        ("cosine", _) => Err("must be `K`".into()),
        ("cosine/squared", _) => Err("must be `K theta0` (degrees)".into()),
        _ => Err("must be angle style cosine or cosine/squared".into()),
    }
}

/// Write `topology` into `data` (whose atoms are the particles, atom id = index + 1): bond and
/// angle types, coefficients and sections, atom style bond (molecular with angles) with each
/// atom's molecule (the bonded clusters numbered from 1 by their smallest id, 0 for an atom
/// without bonds). The
/// error says which styles a file cannot hold together.
pub fn write_topology(topology: &Topology, data: &mut DataFile) -> Result<(), String> {
    let bond_types = topology.bond_types();
    let angle_types = topology.angle_types();
    data.bond_types = bond_types.len() as u32;
    data.angle_types = angle_types.len() as u32;
    data.bond_coeffs = coefficients(bond_types, |s| match *s {
        BondStyle::Harmonic { k, r0 } => ("harmonic", vec![k, r0]),
        BondStyle::Fene { k, r_max } => ("fene", vec![k, r_max, 0.0, 1.0]),
    })?;
    data.angle_coeffs = coefficients(angle_types, |s| match *s {
        AngleStyle::Cosine { k } => ("cosine", vec![k]),
        AngleStyle::CosineSquared { k, theta0 } => ("cosine/squared", vec![k, degrees(theta0)]),
    })?;
    let id = |i: u32| u64::from(i) + 1;
    data.bonds = (topology.bonds().iter().enumerate())
        .map(|(n, b)| lammps_data::Topology {
            id: n as u64 + 1,
            kind: u32::from(b.kind) + 1,
            atoms: [id(b.i), id(b.j)],
        })
        .collect();
    data.angles = (topology.angles().iter().enumerate())
        .map(|(n, a)| lammps_data::Topology {
            id: n as u64 + 1,
            kind: u32::from(a.kind) + 1,
            atoms: [id(a.i), id(a.j), id(a.k)],
        })
        .collect();
    let molecules = molecules(topology);
    // LAMMPS's atom style bond holds no angles; molecular has the same columns and holds both.
    data.atom_style = match data.angles.is_empty() {
        true => lammps_data::AtomStyle::Bond,
        false => lammps_data::AtomStyle::Molecular,
    };
    for atom in &mut data.atoms {
        atom.molecule = Some(molecules[(atom.id - 1) as usize]);
    }
    Ok(())
}

/// `theta` (radians) in degrees: the shortest of the doubles within 4 ulps of
/// `theta.to_degrees()` that `to_radians` turns back into `theta` (that one itself where none
/// does), so that an angle goes through a file unchanged: 105 degrees comes out of
/// `to_degrees` as 105.00000000000001, which reads back as another double.
fn degrees(theta: f64) -> f64 {
    let d = theta.to_degrees();
    let (mut near, mut up, mut down) = (vec![d], d, d);
    for _ in 0..4 {
        (up, down) = (up.next_up(), down.next_down());
        near.extend([up, down]);
    }
    let back = near.into_iter().filter(|x| x.to_radians() == theta);
    back.min_by_key(|x| x.to_string().len()).unwrap_or(d)
}

/// The coefficients of `types` under one style (LAMMPS's `bond_style` or `angle_style`).
fn coefficients<S>(
    types: &[S],
    coeffs: impl Fn(&S) -> (&'static str, Vec<f64>),
) -> Result<Coeffs<u32>, String> {
    let mut out = Coeffs::default();
    for (t, s) in types.iter().enumerate() {
        let (name, c) = coeffs(s);
        if out.style.as_deref().is_some_and(|n| n != name) {
            return Err(format!(
                "types of styles {} and {name}: a data file here holds one bond style and one \
                 angle style",
                out.style.unwrap_or_default()
            ));
        }
        out.style = Some(name.to_string());
        out.by_type.insert(t as u32 + 1, c);
    }
    Ok(out)
}

/// The molecule of each particle: its bonded cluster's number, from 1 in the order of the
/// clusters' smallest ids, or 0 without bonds.
fn molecules(topology: &Topology) -> Vec<u64> {
    let n = topology.particles();
    let mut root: Vec<usize> = (0..n).collect();
    fn find(root: &mut [usize], mut i: usize) -> usize {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    }
    let mut bonded = vec![false; n];
    for b in topology.bonds() {
        let (i, j) = (find(&mut root, b.i as usize), find(&mut root, b.j as usize));
        root[i.max(j)] = i.min(j);
        bonded[b.i as usize] = true;
        bonded[b.j as usize] = true;
    }
    let mut number = vec![0u64; n];
    let mut next = 0;
    for i in 0..n {
        if bonded[i] {
            let r = find(&mut root, i);
            if number[r] == 0 {
                next += 1;
                number[r] = next;
            }
            number[i] = number[r];
        }
    }
    number
}

#[cfg(test)]
mod tests;
