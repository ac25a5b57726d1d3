use super::*;

/// A file as LAMMPS's `write_data` writes one for `atom_style full`, `pair_style dpd`,
/// `bond_style harmonic` (comments, blank lines, image flags), trimmed to three atoms; the
/// velocities out of order.
const FULL: &str = "LAMMPS data file via write_data, version 2 Aug 2023, timestep = 100, units = lj

3 atoms
2 atom types
2 bonds
1 bond types
1 angles
1 angle types

-2.5 2.5 xlo xhi
0 5 ylo yhi
0 6.25 zlo zhi

Atom Type Labels

1 A
2 Wall

Masses

1 1
2 2.5

PairIJ Coeffs # dpd

1 1 25 4.5 1
1 2 40 4.5 1
2 2 25 4.5

Bond Coeffs # harmonic

1 4 0

Angle Coeffs # cosine

1 2

Atoms # full

1 1 1 0 -2 0.5 0.25 0 0 0
3 1 2 0.5 1.5 4.75 6 1 -1 0
2 1 1 -0.5 0 1e-3 3 0 0 2

Velocities

3 0.1 0.2 0.3
1 -1 0 0
2 0 0 1.5e-1

Bonds

1 1 1 2
2 1 2 3

Angles

1 1 1 2 3
";

#[test]
fn a_full_file_is_read_as_written() {
    let f = DataFile::parse(FULL).unwrap();
    assert_eq!(f.bounds, [[-2.5, 2.5], [0.0, 5.0], [0.0, 6.25]]);
    assert_eq!((f.atom_types, f.bond_types, f.angle_types), (2, 1, 1));
    assert_eq!(f.atom_style, AtomStyle::Full);
    assert_eq!(f.masses, [Some(1.0), Some(2.5)]);
    assert_eq!(
        f.type_labels,
        Some(vec!["A".to_string(), "Wall".to_string()])
    );
    assert_eq!(f.atoms.len(), 3);
    let a = &f.atoms[1];
    assert_eq!(
        (a.id, a.molecule, a.kind, a.charge),
        (3, Some(1), 2, Some(0.5))
    );
    assert_eq!((a.position, a.image), ([1.5, 4.75, 6.0], [1, -1, 0]));
    assert_eq!(a.velocity, Some([0.1, 0.2, 0.3]));
    assert_eq!(f.atoms[2].velocity, Some([0.0, 0.0, 0.15]));
    assert_eq!(f.pair_coeffs.style.as_deref(), Some("dpd"));
    assert_eq!(f.pair_coeffs.by_type[&(1, 1)], [25.0, 4.5, 1.0]);
    assert_eq!(f.pair_coeffs.by_type[&(2, 2)], [25.0, 4.5]);
    assert_eq!(f.pair_coeffs.by_type[&(1, 2)], [40.0, 4.5, 1.0]);
    assert_eq!(f.bond_coeffs.style.as_deref(), Some("harmonic"));
    assert_eq!(f.bond_coeffs.by_type[&1], [4.0, 0.0]);
    assert_eq!(f.angle_coeffs.by_type[&1], [2.0]);
    assert_eq!(
        f.bonds[1],
        Topology {
            id: 2,
            kind: 1,
            atoms: [2, 3]
        }
    );
    assert_eq!(f.angles[0].atoms, [1, 2, 3]);
    // `Pair Coeffs` gives the like pairs.
    let like = FULL.replace(
        "PairIJ Coeffs # dpd\n\n1 1 25 4.5 1\n1 2 40 4.5 1\n",
        "Pair Coeffs\n\n1 20 4.5\n",
    );
    let f = DataFile::parse(&like.replace("2 2 25 4.5", "2 30 4.5")).unwrap();
    assert_eq!(f.pair_coeffs.style, None);
    assert_eq!(
        f.pair_coeffs.by_type.keys().collect::<Vec<_>>(),
        [&(1, 1), &(2, 2)]
    );
    assert_eq!(f.pair_coeffs.by_type[&(2, 2)], [30.0, 4.5]);
}

#[test]
fn a_written_file_reads_back_the_same() {
    let f = DataFile::parse(FULL).unwrap();
    let again = DataFile::parse(&f.to_text()).unwrap();
    assert_eq!(again, f);
    // Written in a file and read from it too.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.data");
    f.write(&path).unwrap();
    assert_eq!(DataFile::read(&path).unwrap(), f);
}

/// The size of a file comes from its header alone: the same count and bounds as a full read,
/// and a header error is reported as by `read`, while the sections are not looked at.
/// The coefficient sections come back as written, with their style comments; the others
/// are skipped.
#[test]
fn the_coefficient_sections_are_read_alone() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("full.data");
    std::fs::write(&path, FULL).unwrap();
    let lines = |l: &[&str]| l.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    assert_eq!(
        DataFile::coefficient_lines(&path).unwrap(),
        [
            (
                "PairIJ Coeffs # dpd".to_string(),
                lines(&["1 1 25 4.5 1", "1 2 40 4.5 1", "2 2 25 4.5"])
            ),
            ("Bond Coeffs # harmonic".to_string(), lines(&["1 4 0"])),
            ("Angle Coeffs # cosine".to_string(), lines(&["1 2"])),
        ]
    );
}

#[test]
fn the_size_is_read_from_the_header() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.data");
    std::fs::write(&path, FULL).unwrap();
    let f = DataFile::read(&path).unwrap();
    assert_eq!(DataFile::read_size(&path).unwrap(), (3, f.bounds));
    assert_eq!(f.atoms.len(), 3);
    std::fs::write(&path, FULL.replace("1 A\n", "1\n")).unwrap();
    assert!(DataFile::read(&path).is_err());
    assert_eq!(DataFile::read_size(&path).unwrap(), (3, f.bounds));
    std::fs::write(&path, FULL.replace("3 atoms", "three atoms")).unwrap();
    let e = DataFile::read_size(&path).unwrap_err().to_string();
    assert!(
        e.contains("line 3: section `three atoms` is not read here"),
        "{e}"
    );
}

#[test]
fn the_atom_style_follows_the_comment_or_the_column_count() {
    let atomic = "t\n\n2 atoms\n1 atom types\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\n\
                  Atoms\n\n1 1 0.1 0.2 0.3\n2 1 0.5 0.5 0.5 0 1 0\n";
    let f = DataFile::parse(atomic).unwrap();
    assert_eq!(f.atom_style, AtomStyle::Atomic);
    assert_eq!((f.atoms[0].molecule, f.atoms[1].image), (None, [0, 1, 0]));
    assert_eq!(f.masses, [None]);
    let bond = atomic
        .replace("Atoms", "Atoms # bond")
        .replace("1 1 0.1", "1 7 1 0.1");
    let bond = bond.replace("2 1 0.5", "2 7 1 0.5");
    let f = DataFile::parse(&bond).unwrap();
    assert_eq!(
        (f.atom_style, f.atoms[1].molecule),
        (AtomStyle::Bond, Some(7))
    );
    let again = DataFile::parse(&f.to_text()).unwrap();
    assert_eq!(again, f);
}

#[test]
fn malformed_files_name_the_section_and_line() {
    for (from, to, message) in [
        (
            "2 atom types",
            "2 atom kinds",
            "line 4 (the header): is no header line",
        ),
        (
            "2.5 2.5 xlo",
            "2.5 -3 xlo",
            "line 10 (the header): a box bound needs lo < hi",
        ),
        (
            "2 2.5\n",
            "3 2.5\n",
            "line 22 (section `Masses`): atom type 3 is not in 1 to 2",
        ),
        (
            "2 2 25 4.5\n",
            "2 2 25 x\n",
            "line 28 (section `PairIJ Coeffs`): `x` is not a finite number",
        ),
        (
            "1 1 1 0 -2",
            "1 1 1 0 -2 9",
            "line 40 (section `Atoms`): 11 columns; atom style full has 7",
        ),
        (
            "2 1 2 3\n",
            "2 1 3 3\n",
            "line 53 (section `Bonds`): bond 2 names atom 3 twice: `2 1 3 3`",
        ),
        (
            "2 1 2 3\n",
            "2 1 2 4\n",
            "line 53 (section `Bonds`): bond 2 names atom 4, which is not in Atoms: `2 1 2 4`",
        ),
        (
            "Angles\n",
            "Dihedrals\n",
            "section `Dihedrals` is not read here",
        ),
        (
            "3 0.1 0.2 0.3\n",
            "",
            "section `Velocities` (line 44): 2 lines, the header asks for 3",
        ),
        (
            "Atoms # full",
            "Atoms # sphere",
            "atom style `sphere` is not read here",
        ),
        (
            "1 4 0\n",
            "2 4 0\n",
            "line 32 (section `Bond Coeffs`): bond type 2 is not in 1 to 1",
        ),
        (
            "3 1 2 0.5",
            "2 1 2 0.5",
            "section `Atoms`: atom id 2 appears twice",
        ),
        (
            "1 1 1 2\n2 1 2 3\n",
            "1 1 1 2 3\n2 1 2 3\n",
            "line 52 (section `Bonds`): a bond line is `id type` and 2 atom ids",
        ),
        // A data line starting with a letter is named, not taken for a section heading.
        (
            "3 1 2 0.5",
            "x 1 2 0.5",
            "line 41 (section `Atoms`): `x` is not a number, and no section read here is \
             named so (known: Atom Type Labels, ",
        ),
        // A count in the header whose section is missing.
        (
            "Bonds\n\n1 1 1 2\n2 1 2 3\n",
            "",
            "the header has 2 bonds and no `Bonds` section",
        ),
        (
            "Angles\n\n1 1 1 2 3\n",
            "",
            "the header has 1 angles and no `Angles` section",
        ),
    ] {
        assert!(FULL.contains(from), "{from}");
        let e = DataFile::parse(&FULL.replacen(from, to, 1)).unwrap_err();
        assert!(e.contains(message), "{from:?} -> {to:?}: {e}");
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.data");
    std::fs::write(&path, FULL.replace("2 atom types", "2 atom kinds")).unwrap();
    let e = DataFile::read(&path).unwrap_err().to_string();
    assert!(
        e.starts_with(&format!("{}: line 4 (the header)", path.display())),
        "{e}"
    );
}
