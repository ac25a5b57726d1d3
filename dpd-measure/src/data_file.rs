//! LAMMPS data files as a run's start (`init = "FILE.data"`) and as its end (`write_data`),
//! in LAMMPS's own conventions so that one file means one system in both engines: `pair_style
//! dpd` coefficients `A gamma [cutoff]` (F = A (1 - r / r_c), sigma^2 = 2 gamma k_B T), the
//! box `[lo, hi)` per axis, types and ids from 1. The file format is `dpd_trajectory`'s.

use crate::data_bonds::write_topology;
use dpd_core::{ParamError, System};
use dpd_trajectory::lammps_data::{Atom, AtomStyle, Coeffs, DataFile};
use dpd_trajectory::Frame;
use std::collections::BTreeMap;

/// The particles of a data file as a frame: in the order of their atom ids, positions less
/// the box's lower corner wrapped into `[0, L)`, type ids from 0 named by the `Atom Type
/// Labels` (else "1", "2", ...), masses from `Masses` (none when it gives none).
pub fn frame_of(data: &DataFile) -> Result<Frame, String> {
    let mut atoms: Vec<&Atom> = data.atoms.iter().collect();
    atoms.sort_by_key(|a| a.id);
    let lengths = data.bounds.map(|[lo, hi]| hi - lo);
    let wrapped = |a: &Atom| {
        std::array::from_fn(|d| (a.position[d] - data.bounds[d][0]).rem_euclid(lengths[d]))
    };
    let masses = match data.masses.iter().position(Option::is_none) {
        None => Some(
            atoms
                .iter()
                .map(|a| data.masses[a.kind as usize - 1].unwrap_or(1.0))
                .collect(),
        ),
        Some(_) if data.masses.iter().all(Option::is_none) => None,
        Some(t) => {
            return Err(format!(
                "section `Masses` gives no mass for atom type {}",
                t + 1
            ))
        }
    };
    let velocities = atoms.iter().map(|a| a.velocity).collect::<Option<Vec<_>>>();
    Ok(Frame {
        // A data file holds no step or time: a run from it counts them from 0.
        step: 0,
        time: 0.0,
        dt: 0.0,
        box_lengths: lengths,
        positions: atoms.iter().map(|a| wrapped(a)).collect(),
        velocities,
        images: Some(atoms.iter().map(|a| a.image).collect()),
        typeid: atoms.iter().map(|a| a.kind - 1).collect(),
        types: match &data.type_labels {
            Some(labels) => labels.clone(),
            None => (1..=data.atom_types).map(|t| t.to_string()).collect(),
        },
        masses,
        log: Vec::new(),
        bonds: None,
    })
}

/// The repulsions `a[i][j]` of the file's `pair_style dpd` coefficients (`None` without
/// them). Every pair of types needs its coefficients (pair dpd does not mix), every gamma must
/// be the scene's `gamma` and every cut-off 1 (one friction and one cut-off for all pairs).
pub fn repulsions(data: &DataFile, gamma: f64) -> Result<Option<Vec<Vec<f64>>>, ParamError> {
    let coeffs = &data.pair_coeffs;
    if coeffs.by_type.is_empty() {
        return Ok(None);
    }
    if let Some(style) = coeffs.style.as_deref().filter(|s| *s != "dpd") {
        return Err(ParamError::new(
            "init: Pair Coeffs",
            style,
            "must be pair_style dpd (A gamma [cutoff])",
        ));
    }
    let t = data.atom_types as usize;
    let mut a = vec![vec![0.0; t]; t];
    for i in 1..=data.atom_types {
        for j in i..=data.atom_types {
            let key = format!("init: Pair Coeffs {i} {j}");
            let c = coeffs.by_type.get(&(i, j)).ok_or_else(|| {
                ParamError::new(
                    &key,
                    "missing",
                    "pair dpd needs the coefficients of every pair of types (PairIJ Coeffs)",
                )
            })?;
            if !(2..=3).contains(&c.len()) {
                return Err(ParamError::new(
                    &key,
                    format!("{c:?}"),
                    "must be A gamma [cutoff]",
                ));
            }
            if c[1] != gamma {
                return Err(ParamError::new(
                    &key,
                    format!("gamma {}", c[1]),
                    format!(
                        "must be the scene's gamma = {gamma} (one friction for all pairs): \
                         set gamma = {} in the scene",
                        c[1]
                    ),
                ));
            }
            if c.len() == 3 && c[2] != 1.0 {
                return Err(ParamError::new(
                    &key,
                    format!("cutoff {}", c[2]),
                    "must be 1 (r_c)",
                ));
            }
            a[i as usize - 1][j as usize - 1] = c[0];
            a[j as usize - 1][i as usize - 1] = c[0];
        }
    }
    Ok(Some(a))
}

/// Checks that a data file's repulsions `file` are the scene's `scene` (types named `names`);
/// the error names the first pair that differs.
pub fn same_repulsions(
    file: &[Vec<f64>],
    scene: &[Vec<f64>],
    names: &[String],
) -> Result<(), ParamError> {
    for (i, row) in file.iter().enumerate() {
        for (j, &a) in row.iter().enumerate().skip(i) {
            if a != scene[i][j] {
                return Err(ParamError::new(
                    format!("init: Pair Coeffs {} {}", i + 1, j + 1),
                    format!("A {a}"),
                    format!(
                        "must be the scene's a of {}-{} = {} (or leave the pairs to one of them)",
                        names[i], names[j], scene[i][j]
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The state of `sys` as a data file of atom style atomic, particles by id (atom id = id + 1),
/// positions in `[0, L)`, with the type names `names` as `Atom Type Labels`, `Masses` (each
/// type's mass; the error names a type whose particles differ in mass), `Velocities` and the
/// `pair_style dpd` coefficients of every pair of types; with a topology, its bonds and angles
/// (see [`write_topology`]).
pub fn data_of(sys: &System, names: &[String], title: &str) -> Result<DataFile, String> {
    let params = sys.params();
    let types = params.types();
    let mut masses = vec![None; types];
    let mut atoms = Vec::with_capacity(sys.len());
    for k in 0..sys.len() {
        let (t, m) = (usize::from(sys.kinds()[k]), sys.masses()[k]);
        match masses[t] {
            Some(seen) if seen != m => {
                return Err(format!(
                    "the particles of type {} have masses {seen} and {m}; a data file has one \
                     mass per type",
                    t + 1
                ))
            }
            _ => masses[t] = Some(m),
        }
        let (q, p) = (sys.positions()[k], sys.momenta()[k]);
        atoms.push(Atom {
            id: u64::from(sys.ids()[k]) + 1,
            molecule: None,
            kind: t as u32 + 1,
            charge: None,
            position: q.into(),
            image: [0; 3],
            velocity: Some((p / m).into()),
        });
    }
    atoms.sort_by_key(|a| a.id);
    let mut by_type = BTreeMap::new();
    for i in 0..types {
        for j in i..types {
            let a = params.a(i as u16, j as u16);
            by_type.insert(
                (i as u32 + 1, j as u32 + 1),
                vec![a, params.gamma(), params.rc()],
            );
        }
    }
    let lengths: [f64; 3] = sys.boundary().lengths().into();
    let mut data = DataFile {
        title: title.to_string(),
        bounds: lengths.map(|l| [0.0, l]),
        atom_types: types as u32,
        bond_types: 0,
        angle_types: 0,
        atom_style: AtomStyle::Atomic,
        masses,
        type_labels: Some(names.to_vec()),
        atoms,
        bonds: Vec::new(),
        angles: Vec::new(),
        pair_coeffs: Coeffs {
            style: Some("dpd".into()),
            by_type,
        },
        bond_coeffs: Coeffs::default(),
        angle_coeffs: Coeffs::default(),
    };
    if let Some(topology) = sys.topology() {
        write_topology(topology, &mut data)?;
    }
    Ok(data)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    const MIXTURE: &str = "n = 120\n[[species]]\nname = \"A\"\ncount = 40\nmass = 2.0\n\
                           [[species]]\nname = \"B\"\ncount = 80\n\
                           [pairs]\nA-A = { a = 25.0 }\nB-B = { a = 30.0 }\nA-B = { a = 40.0 }\n";

    /// A mixture written as a data file and started from it is the same system: positions,
    /// types, masses and repulsions exactly, velocities to rounding (written as p / m).
    #[test]
    fn a_system_written_as_a_data_file_starts_again_from_it() {
        let scene = Scene::from_toml(MIXTURE, "t").unwrap();
        let mut sys = scene.system(0.05, 3).unwrap();
        let aboba = dpd_schemes::registry::resolve("aboba").unwrap();
        sys.advance(aboba.as_ref(), 20).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("s.data");
        data_of(&sys, &scene.type_names(2), "t")
            .unwrap()
            .write(&file)
            .unwrap();
        let init = format!("n = 120\ninit = {:?}\n", file.display().to_string());
        let again = Scene::from_toml(&init, "t").unwrap();
        again.validate().unwrap();
        let copy = again.system(0.05, 3).unwrap();
        let by_id = |s: &System| {
            let mut v: Vec<_> = (0..s.len())
                .map(|k| {
                    (
                        s.ids()[k],
                        s.positions()[k],
                        s.momenta()[k],
                        s.masses()[k],
                        s.kinds()[k],
                    )
                })
                .collect();
            v.sort_by_key(|x| x.0);
            v
        };
        for (a, b) in by_id(&sys).into_iter().zip(by_id(&copy)) {
            assert_eq!((a.0, a.1, a.3, a.4), (b.0, b.1, b.3, b.4));
            assert!(
                (a.2 - b.2).norm() <= 1e-15 * a.2.norm().max(1.0),
                "{a:?} {b:?}"
            );
        }
        for (i, j) in [(0, 0), (0, 1), (1, 1)] {
            assert_eq!(copy.params().a(i, j), sys.params().a(i, j));
        }
    }

    #[test]
    fn pair_coefficients_the_engine_cannot_hold_are_named() {
        let scene = Scene::from_toml(MIXTURE, "t").unwrap();
        let data = data_of(&scene.system(0.05, 3).unwrap(), &scene.type_names(2), "t").unwrap();
        let with = |pair: (u32, u32), c: Vec<f64>| {
            let mut d = data.clone();
            d.pair_coeffs.by_type.insert(pair, c);
            repulsions(&d, 4.5).unwrap_err().to_string()
        };
        let e = with((1, 2), vec![40.0, 9.0]);
        assert!(
            e.contains("Pair Coeffs 1 2 = gamma 9") && e.contains("gamma = 9"),
            "{e}"
        );
        let e = with((2, 2), vec![25.0, 4.5, 0.8]);
        assert!(e.contains("Pair Coeffs 2 2 = cutoff 0.8"), "{e}");
        let mut missing = data.clone();
        missing.pair_coeffs.by_type.remove(&(1, 2));
        let e = repulsions(&missing, 4.5).unwrap_err().to_string();
        assert!(e.contains("invalid init: Pair Coeffs 1 2 = missing"), "{e}");
        // The mixture starts from its own file; with other repulsions the pair is named.
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("s.data");
        data.write(&file).unwrap();
        let init = format!("init = {:?}\n", file.display().to_string());
        let own = Scene::from_toml(&(init.clone() + MIXTURE), "t").unwrap();
        own.system(0.05, 3).unwrap();
        let other = Scene::from_toml(&(init + &MIXTURE.replace("40.0", "41.0")), "t").unwrap();
        let e = other.system(0.05, 3).unwrap_err().to_string();
        assert!(
            e.contains("Pair Coeffs 1 2 = A 40: must be the scene's a of A-B = 41"),
            "{e}"
        );
        let mut renamed = data.clone();
        renamed.type_labels = Some(vec!["A".into(), "C".into()]);
        renamed.write(&file).unwrap();
        let e = own.system(0.05, 3).unwrap_err().to_string();
        assert!(e.contains("Atom Type Labels [\"A\", \"C\"] are not"), "{e}");
    }
}
