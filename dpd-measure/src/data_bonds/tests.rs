use super::*;
use crate::data_file::data_of;
use crate::scene::Scene;

const SPECIES: &str = "n = 200\n\
                       [[species]]\nname = \"A\"\nfraction = 0.5\n\
                       [[species]]\nname = \"B\"\nfraction = 0.5\n\
                       [pairs]\nA-A = { a = 25.0 }\nB-B = { a = 25.0 }\nA-B = { a = 30.0 }\n";

const CHAINS: &str = "[[bond_types]]\nname = \"soft\"\nstyle = \"harmonic\"\nk = 2.0\n\
                      [[bond_types]]\nname = \"stiff\"\nstyle = \"harmonic\"\nk = 50.0\n\
                      r0 = 0.7\n\
                      [[angle_types]]\nname = \"bend\"\nstyle = \"cosine_squared\"\nk = 3.0\n\
                      theta0 = 105.0\n\
                      [[molecules]]\nlength = 5\ncount = 10\nbeads = \"A A B B B\"\n\
                      bond = \"soft\"\nangle = \"bend\"\n\
                      [[molecules]]\nlength = 3\ncount = 5\nbeads = \"A\"\nbond = \"stiff\"\n";

/// The data file of a bonded system, as text.
fn written(scene: &Scene) -> String {
    let sys = scene.system(0.05, 2).unwrap();
    data_of(&sys, &scene.type_names(2), "t").unwrap().to_text()
}

/// A melt with two bond types, an angle type and solvent written as a data file starts again
/// with the same topology (bonds and angles by id; coefficients exactly, theta0 too: 105
/// degrees, which to_degrees turns into 105.00000000000001 and that back into another
/// double, is written 105) and the same positions; the file has atom style molecular (bond holds
/// no angles) with one molecule per chain and 0 for the solvent.
#[test]
fn bonds_and_angles_go_through_a_data_file() {
    let scene = Scene::from_toml(&format!("{SPECIES}{CHAINS}"), "t").unwrap();
    scene.validate().unwrap();
    let sys = scene.system(0.05, 2).unwrap();
    let text = written(&scene);
    assert!(
        text.contains("Bond Coeffs # harmonic\n\n1 2 0\n2 50 0.7\n"),
        "{text}"
    );
    assert!(
        text.contains("Angle Coeffs # cosine/squared\n\n1 3 105\n"),
        "{text}"
    );
    assert!(text.contains("Atoms # molecular"), "{text}");
    let data = DataFile::parse(&text).unwrap();
    let mol = |id: u64| data.atoms.iter().find(|a| a.id == id).unwrap().molecule;
    assert_eq!(
        (mol(1), mol(5), mol(6), mol(51), mol(66)),
        (Some(1), Some(1), Some(2), Some(11), Some(0))
    );
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("melt.data");
    std::fs::write(&file, &text).unwrap();
    let init = format!("init = {:?}\n{SPECIES}", file.display().to_string());
    let again = Scene::from_toml(&init, "t").unwrap();
    again.validate().unwrap();
    let copy = again.system(0.05, 2).unwrap();
    let (a, b) = (sys.topology().unwrap(), copy.topology().unwrap());
    assert_eq!(
        (a.bonds(), a.angles(), a.bond_types()),
        (b.bonds(), b.angles(), b.bond_types())
    );
    let AngleStyle::CosineSquared { theta0, .. } = b.angle_types()[0] else {
        panic!("{:?}", b.angle_types());
    };
    assert_eq!(theta0, 105f64.to_radians());
    let by_id = |s: &dpd_core::System| {
        let mut v: Vec<_> = s
            .ids()
            .iter()
            .zip(s.positions())
            .map(|(&i, &q)| (i, q))
            .collect();
        v.sort_by_key(|x| x.0);
        v
    };
    assert_eq!(by_id(&sys), by_id(&copy));
}

/// Coefficients the engine cannot hold, or that are missing, are named with their section and
/// type; a bond to a missing atom or to the same atom twice with its line.
#[test]
fn bad_bonded_sections_are_named() {
    let scene = Scene::from_toml(&format!("{SPECIES}{CHAINS}"), "t").unwrap();
    let text = written(&scene);
    let error = |from: &str, to: &str| {
        assert!(text.contains(from), "{from}");
        let data = DataFile::parse(&text.replacen(from, to, 1)).map_err(|e| e.to_string())?;
        topology_of(&data).map(|_| ()).map_err(|e| e.to_string())
    };
    for (from, to, says) in [
        (
            "2 50 0.7\n",
            "",
            "section `Bond Coeffs` (line 29): 1 lines, the header asks for 2",
        ),
        (
            "Bond Coeffs # harmonic",
            "Bond Coeffs",
            "Bond Coeffs 1 = no style",
        ),
        (
            "Bond Coeffs # harmonic",
            "Bond Coeffs # morse",
            "must be bond style harmonic or fene",
        ),
        (
            "1 2 0\n",
            "1 2 0 1\n",
            "Bond Coeffs 1 = harmonic [2.0, 0.0, 1.0]: must be `K r0`",
        ),
        (
            "Angle Coeffs # cosine/squared",
            "Angle Coeffs # harmonic",
            "cosine or cosine/squared",
        ),
        ("\n1 1 1 2\n", "\n1 1 1 1\n", "bond 1 names atom 1 twice"),
        (
            "\n1 1 1 2\n",
            "\n1 1 1 999\n",
            "bond 1 names atom 999, which is not in Atoms",
        ),
    ] {
        let e = error(from, to).unwrap_err();
        assert!(e.contains(says), "{from:?} -> {to:?}: {e}");
    }
    let fene = text.replace(
        "Bond Coeffs # harmonic\n\n1 2 0\n2 50 0.7",
        "Bond Coeffs # fene\n\n1 30 1.5 1 1\n2 30 1.5 0 1",
    );
    let data = DataFile::parse(&fene).unwrap();
    let e = topology_of(&data).unwrap_err().to_string();
    assert!(
        e.contains("Bond Coeffs 1 = fene [30.0, 1.5, 1.0, 1.0]: must have epsilon 0"),
        "{e}"
    );
    let e = error("\n1 1 1 2\n", "\n1 1 1 999\n").unwrap_err();
    assert!(
        e.starts_with("line ") && e.contains("(section `Bonds`)"),
        "{e}"
    );
}

/// A data file whose FENE bond starts at or beyond R0 is refused naming the bond as the file
/// does, by its id and atom ids (here renumbered, so that they are not the engine's indices).
#[test]
fn a_fene_bond_stretched_in_the_file_is_named_by_its_id() {
    let melt = "n = 200\n[[bond_types]]\nname = \"f\"\nstyle = \"fene\"\nk = 30.0\nr_max = 1.5\n\
                [[molecules]]\nlength = 5\ncount = 10\nbond = \"f\"\n";
    let scene = Scene::from_toml(melt, "t").unwrap();
    let sys = scene.system(0.05, 2).unwrap();
    let mut data = data_of(&sys, &scene.type_names(1), "t").unwrap();
    for b in &mut data.bonds {
        b.id += 100;
    }
    let first = data.atoms.iter().find(|a| a.id == 1).unwrap().position;
    let second = data.atoms.iter_mut().find(|a| a.id == 2).unwrap();
    second.position = [first[0] + 1.55, first[1], first[2]];
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("stretched.data");
    data.write(&file).unwrap();
    let init = format!("init = {:?}\n", file.display().to_string());
    let e = Scene::from_toml(&init, "t")
        .unwrap()
        .system(0.05, 1)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("invalid init: Bonds: bond 101 = atoms 1 and 2 of the file (ids 0, 1 at")
            && e.ends_with("a FENE bond must start shorter than its R0"),
        "{e}"
    );
}
