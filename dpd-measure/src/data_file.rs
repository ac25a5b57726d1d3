//! LAMMPS data files as a run's start (`init = "FILE.data"`) and as its end (`write_data`),
//! in LAMMPS's own conventions so that one file means one system in both engines: `pair_style
//! dpd` coefficients `A gamma [cutoff]` (F = A (1 - r / r_c), sigma^2 = 2 gamma k_B T), the
//! box `[lo, hi)` per axis, types and ids from 1. The file format is `dpd_trajectory`'s.

use crate::data_bonds::write_topology;
use crate::pair_coefficients::PairCoefficients;
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

/// The file's `pair_style dpd` coefficients `A gamma [cutoff]` of every pair of types
/// (`None` without them; a missing cutoff is 1). Every pair of types needs its coefficients
/// (pair dpd does not mix); a cutoff must be in (0, 1], the largest, which sizes the cells.
pub fn pair_coefficients(data: &DataFile) -> Result<Option<PairCoefficients>, ParamError> {
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
    let mut matrices = [
        vec![vec![0.0; t]; t],
        vec![vec![0.0; t]; t],
        vec![vec![1.0; t]; t],
    ];
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
            let valid = (2..=3).contains(&c.len())
                && c[0] >= 0.0
                && c[1] >= 0.0
                && c.get(2).is_none_or(|&rc| rc > 0.0 && rc <= 1.0);
            if !valid {
                return Err(ParamError::new(
                    &key,
                    format!("{c:?}"),
                    "must be A >= 0, gamma >= 0 [and a cutoff in (0, 1]: the largest, 1, sizes \
                     the cells]",
                ));
            }
            for (m, &v) in matrices.iter_mut().zip(c) {
                m[i as usize - 1][j as usize - 1] = v;
                m[j as usize - 1][i as usize - 1] = v;
            }
        }
    }
    let [a, gamma, rc] = matrices;
    Ok(Some(PairCoefficients { a, gamma, rc }))
}

/// Checks that a data file's pair coefficients `file` are the scene's `scene` (types named
/// `names`); the error names the first pair that differs.
pub fn same_coefficients(
    file: &PairCoefficients,
    scene: &PairCoefficients,
    names: &[String],
) -> Result<(), ParamError> {
    match file.first_difference(scene) {
        None => Ok(()),
        Some((i, j)) => Err(ParamError::new(
            format!("init: Pair Coeffs {} {}", i + 1, j + 1),
            format!("A gamma cutoff = {}", spaced(file.of(i, j))),
            format!(
                "must be the scene's {}-{} = {} (or leave the pairs to one of them)",
                names[i],
                names[j],
                spaced(scene.of(i, j))
            ),
        )),
    }
}

/// Numbers separated by spaces, as a data file's line has them.
fn spaced(values: [f64; 3]) -> String {
    values.map(|v| v.to_string()).join(" ")
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
            let (ti, tj) = (i as u16, j as u16);
            let (gamma, _) = params.friction(ti, tj);
            by_type.insert(
                (i as u32 + 1, j as u32 + 1),
                vec![params.a(ti, tj), gamma, params.rc_of(ti, tj)],
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
    /// types, masses and pair coefficients (a pair's own friction and cut-off too) exactly,
    /// velocities to rounding (written as p / m).
    #[test]
    fn a_system_written_as_a_data_file_starts_again_from_it() {
        let own = "A-B = { a = 40.0, gamma = 9.0, rc = 0.8 }";
        let scene = Scene::from_toml(&MIXTURE.replace("A-B = { a = 40.0 }", own), "t").unwrap();
        let mut sys = scene.system(0.05, 3).unwrap();
        let aboba = dpd_schemes::registry::resolve("aboba").unwrap();
        sys.advance(aboba.as_ref(), 20).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("s.data");
        data_of(&sys, &scene.type_names(2), "t")
            .unwrap()
            .write(&file)
            .unwrap();
        let init = format!("init = {:?}\n", file.display().to_string());
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
            let (p, q) = (copy.params(), sys.params());
            assert_eq!(p.a(i, j), q.a(i, j));
            assert_eq!(p.friction(i, j), q.friction(i, j));
            assert_eq!(p.rc_of(i, j), q.rc_of(i, j));
        }
        assert_eq!(copy.params().friction(0, 1).0, 9.0);
        assert_eq!(copy.params().rc_of(0, 1), 0.8);
    }

    #[test]
    fn per_pair_friction_and_cutoff_are_read_and_bad_coefficients_named() {
        let scene = Scene::from_toml(MIXTURE, "t").unwrap();
        let data = data_of(&scene.system(0.05, 3).unwrap(), &scene.type_names(2), "t").unwrap();
        let with = |pairs: &[((u32, u32), Vec<f64>)]| {
            let mut d = data.clone();
            for (pair, c) in pairs {
                d.pair_coeffs.by_type.insert(*pair, c.clone());
            }
            pair_coefficients(&d)
        };
        let c = with(&[((1, 2), vec![40.0, 9.0]), ((2, 2), vec![25.0, 4.5, 0.8])])
            .unwrap()
            .unwrap();
        assert_eq!(c.gamma, [[4.5, 9.0], [9.0, 4.5]]);
        assert_eq!(c.rc, [[1.0, 1.0], [1.0, 0.8]]);
        let e = with(&[((2, 2), vec![25.0, 4.5, 1.5])])
            .unwrap_err()
            .to_string();
        assert!(e.contains("Pair Coeffs 2 2 = [25.0, 4.5, 1.5]"), "{e}");
        assert!(e.contains("cutoff in (0, 1]"), "{e}");
        let e = with(&[((1, 1), vec![25.0, -1.0])]).unwrap_err().to_string();
        assert!(e.contains("Pair Coeffs 1 1 = [25.0, -1.0]"), "{e}");
        let mut missing = data.clone();
        missing.pair_coeffs.by_type.remove(&(1, 2));
        let e = pair_coefficients(&missing).unwrap_err().to_string();
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
            e.contains(
                "Pair Coeffs 1 2 = A gamma cutoff = 40 4.5 1: must be the scene's A-B = 41 4.5 1"
            ),
            "{e}"
        );
        let mut renamed = data.clone();
        renamed.type_labels = Some(vec!["A".into(), "C".into()]);
        renamed.write(&file).unwrap();
        let e = own.system(0.05, 3).unwrap_err().to_string();
        assert!(e.contains("Atom Type Labels [\"A\", \"C\"] are not"), "{e}");
    }
}
