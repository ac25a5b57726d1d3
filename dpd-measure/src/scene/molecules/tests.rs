use super::*;
use dpd_core::bonded::{AngleStyle, BondStyle};

fn molecules(text: &str) -> Molecules {
    super::super::section::take(&mut toml::from_str(text).unwrap()).unwrap()
}

const MELT: &str = "[[bond_types]]\nname = \"spring\"\nstyle = \"harmonic\"\nk = 2.0\n\
                    [[bond_types]]\nname = \"fene\"\nstyle = \"fene\"\nk = 30.0\nr_max = 1.5\n\
                    [[angle_types]]\nname = \"bend\"\nstyle = \"cosine_squared\"\nk = 3.0\n\
                    theta0 = 120.0\n\
                    [[molecules]]\nlength = 4\ncount = 3\nbeads = \"A A B B\"\n\
                    bond = \"spring\"\nangle = \"bend\"\n\
                    [[molecules]]\nlength = 5\nfraction = 0.5\nbeads = \"B\"\nbond = \"fene\"\n";

fn species() -> Vec<String> {
    vec!["A".into(), "B".into()]
}

fn cx<'a>(names: &'a [String], counts: &'a [usize]) -> Context<'a> {
    Context {
        species: names,
        counts,
        kbt: 1.0,
        shortest_edge: 6.0,
    }
}

#[test]
fn chains_resolve_to_counts_bead_types_and_typical_steps() {
    let names = species();
    let m = molecules(MELT);
    let plans = m.plan(40, &cx(&names, &[14, 26])).unwrap();
    assert_eq!(plans.len(), 2);
    assert_eq!(plans[0].chains, 3);
    assert_eq!(plans[0].beads, [0, 0, 1, 1]);
    assert_eq!((plans[0].bond, plans[0].angle), (0, Some(0)));
    // Harmonic k r^2 alone: <r^2> = 3 kT / (2k) = 3/4.
    assert_eq!(plans[0].step, 0.75f64.sqrt());
    // Half of 40 particles in 5-bead chains: 4 chains.
    assert_eq!(plans[1].chains, 4);
    assert_eq!(plans[1].beads, [1; 5]);
    // FENE k r^2 / 2 near 0: sqrt(3 kT / k) = sqrt(0.1), below r_max / 2.
    assert_eq!(plans[1].step, 0.1f64.sqrt());
    assert_eq!(
        m.angle_styles().unwrap(),
        [AngleStyle::CosineSquared {
            k: 3.0,
            theta0: 120f64.to_radians()
        }]
    );
    let r0 = BondStyle::Harmonic { k: 50.0, r0: 0.7 };
    assert_eq!(typical_length(r0, 1.0), 0.7);
    let weak = BondStyle::Fene { k: 1.0, r_max: 1.0 };
    assert_eq!(typical_length(weak, 1.0), 0.5);
}

#[test]
fn errors_name_the_key_the_value_and_what_is_valid() {
    let names = species();
    let counts = [14, 26];
    for (text, key, says) in [
        (
            MELT.replace("length = 4", "length = 1"),
            "molecules[0].length",
            "2 to",
        ),
        (
            MELT.replace("count = 3\n", ""),
            "molecules[0]",
            "either count",
        ),
        (
            MELT.replace("fraction = 0.5", "fraction = 1.5"),
            "molecules[1].fraction",
            "(0, 1]",
        ),
        (
            MELT.replace("A A B B", "A B"),
            "molecules[0].beads",
            "one per bead (4)",
        ),
        (
            MELT.replace("A A B B", "A A B C"),
            "molecules[0].beads",
            "[[species]] (A, B)",
        ),
        (
            MELT.replace("bond = \"spring\"", "bond = \"x\""),
            "molecules[0].bond",
            "spring, fene",
        ),
        (
            MELT.replace("angle = \"bend\"", "angle = \"x\""),
            "molecules[0].angle",
            "bend",
        ),
        (
            MELT.replace("\"harmonic\"", "\"morse\""),
            "bond_types[0].style",
            "\"fene\"",
        ),
        (
            MELT.replace("k = 2.0", "k = -2.0"),
            "bond_types[0].k",
            "> 0",
        ),
        (
            MELT.replace("r_max = 1.5", "r0 = 1.5"),
            "bond_types[1].r0",
            "not a key",
        ),
        (
            MELT.replace("theta0 = 120.0", "theta0 = 200.0"),
            "angle_types[0].theta0",
            "180",
        ),
        (
            MELT.replace("\"fene\"\nstyle", "\"spring\"\nstyle"),
            "bond_types[1].name",
            "differ",
        ),
        (
            MELT.replace("bond = \"fene\"", "bond = \"fene\"\nstep = 1.5"),
            "molecules[1].step",
            "r_max = 1.5: a longer bond blows up",
        ),
        (
            MELT.replace("bond = \"fene\"", "bond = \"fene\"\nstep = 3.5\n")
                .replace("r_max = 1.5", "r_max = 9.0"),
            "molecules[1].step",
            "half the shortest box edge",
        ),
        (
            MELT.replace("fraction = 0.5", "fraction = 1.0"),
            "molecules",
            "fit in",
        ),
        (
            MELT.replace("beads = \"B\"", "beads = \"A\""),
            "molecules",
            "species A has 14",
        ),
    ] {
        let e = molecules(&text).plan(40, &cx(&names, &counts)).unwrap_err();
        assert_eq!(e.field, key, "{text}: {e}");
        assert!(e.to_string().contains(says), "{e}");
    }
    let mut keys = toml::from_str(&MELT.replace("count = 3", "count = 3\nsize = 2")).unwrap();
    let e = super::super::section::take::<Molecules>(&mut keys).unwrap_err();
    assert!(e.contains("unknown field `size`"), "{e}");
}
