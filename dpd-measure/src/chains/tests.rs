use super::*;

fn plan(chains: usize, beads: &[u16], step: f64) -> ChainPlan {
    ChainPlan {
        chains,
        beads: beads.to_vec(),
        bond: 0,
        angle: Some(0),
        step,
    }
}

fn cube(l: f64) -> PeriodicBox {
    PeriodicBox::cubic(l).unwrap()
}

/// Mean and standard error of the mean.
fn mean_se(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

#[test]
fn chains_take_consecutive_ids_and_the_solvent_the_types_left() {
    let plans = [plan(2, &[0, 0, 1], 0.5), plan(1, &[1, 1], 0.5)];
    let chains: Vec<Chain> = layout(&plans).into_iter().map(|(c, _)| c).collect();
    assert_eq!(chains, [vec![0, 1, 2], vec![3, 4, 5], vec![6, 7]]);
    // 5 A and 6 B: the chains use 4 of each, the solvent is 1 A and 2 B.
    assert_eq!(kinds(&plans, &[5, 6]), [0, 0, 1, 0, 0, 1, 1, 1, 0, 1, 1]);
    let (bonds, angles) = bonds_and_angles(&[
        plan(1, &[0; 4], 0.5),
        ChainPlan {
            angle: None,
            bond: 1,
            ..plan(1, &[0; 2], 0.5)
        },
    ]);
    let bonds: Vec<_> = bonds
        .iter()
        .map(|b| [b.i, b.j, u32::from(b.kind)])
        .collect();
    assert_eq!(bonds, [[0, 1, 0], [1, 2, 0], [2, 3, 0], [4, 5, 1]]);
    let angles: Vec<_> = angles
        .iter()
        .map(|a| [a.i, a.j, a.k, u32::from(a.kind)])
        .collect();
    assert_eq!(angles, [[0, 1, 2, 0], [1, 2, 3, 0]]);
}

/// A freely jointed chain of n beads and step b has <R_ee^2> = (n - 1) b^2 and <R_g^2> =
/// b^2 (n^2 - 1) / (6 n) exactly (independent steps of length b, uniform directions). 2000
/// chains of 10 beads, b = 0.8, in a box of edge 5 (the walks cross its faces, so the
/// positions must be unwrapped): each mean within four standard errors, which are under 3 %
/// of the means, so a walk with the wrong step, correlated steps or a wrong unwrapping
/// (R_ee bounded by the box) fails. Every bond is b to rounding.
#[test]
fn random_walks_are_freely_jointed_chains_of_the_step_length() {
    let (n, b) = (10, 0.8);
    let plans = [plan(2000, &[0; 10], b)];
    let bx = cube(5.0);
    let q = random_walks(&plans, &bx, 7);
    assert_eq!(q.len(), 20_000);
    let l = bx.lengths();
    assert!(q.iter().all(|x| (0..3).all(|a| x[a] >= 0.0 && x[a] < l[a])));
    let (mut ree, mut rg) = (Vec::new(), Vec::new());
    for (chain, _) in layout(&plans) {
        let x = unwrapped(&chain, |id| q[id as usize], &bx);
        for w in x.windows(2) {
            assert!(((w[1] - w[0]).norm() - b).abs() < 1e-12);
        }
        ree.push(end_to_end_squared(&x));
        rg.push(gyration_squared(&x));
    }
    let nf = n as f64;
    for (name, values, want) in [
        ("R_ee^2", &ree, (nf - 1.0) * b * b),
        ("R_g^2", &rg, b * b * (nf * nf - 1.0) / (6.0 * nf)),
    ] {
        let (mean, se) = mean_se(values);
        assert!(se < 0.03 * want, "{name}: standard error {se}");
        assert!(
            (mean - want).abs() < 4.0 * se,
            "{name}: {mean} +- {se}, want {want}"
        );
    }
    // Another seed, other walks.
    assert_ne!(random_walks(&plans, &bx, 8)[5], q[5]);
}

#[test]
fn sizes_of_known_configurations() {
    // A unit square: every corner 1/sqrt(2) from the centre.
    let square =
        [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]].map(|[x, y]| Vec3::new(x, y, 2.0));
    assert!((gyration_squared(&square) - 0.5).abs() < 1e-15);
    assert_eq!(end_to_end_squared(&square), 1.0);
    // A straight rod of n beads spaced b: R_g^2 = b^2 (n^2 - 1) / 12.
    let rod: Vec<Vec3> = (0..7)
        .map(|k| Vec3::new(0.3 * k as f64, 0.0, 0.0))
        .collect();
    let want = 0.09 * 48.0 / 12.0;
    assert!((gyration_squared(&rod) - want).abs() < 1e-14);
    assert!((end_to_end_squared(&rod) - 1.8 * 1.8).abs() < 1e-14);
}

/// A chain that crosses the box's faces (edge 5) is made whole again: beads stored at x = 4.6,
/// 0.1, 0.6 and y = 0.2, 4.9, 4.4 are at x = 4.6, 5.1, 5.6 and y = 0.2, -0.1, -0.6.
#[test]
fn chains_are_unwrapped_across_the_boundary() {
    let bx = cube(5.0);
    let stored = [
        Vec3::new(4.6, 0.2, 1.0),
        Vec3::new(0.1, 4.9, 1.0),
        Vec3::new(0.6, 4.4, 1.0),
    ];
    let x = unwrapped(&[0, 1, 2], |id| stored[id as usize], &bx);
    let want = [
        Vec3::new(4.6, 0.2, 1.0),
        Vec3::new(5.1, -0.1, 1.0),
        Vec3::new(5.6, -0.6, 1.0),
    ];
    for (a, b) in x.iter().zip(&want) {
        assert!((a - b).norm() < 1e-12, "{a} {b}");
    }
    assert!((end_to_end_squared(&x) - 1.64).abs() < 1e-12);
    // Stored order differs from chain order: the bonds decide.
    let x = unwrapped(&[2, 1, 0], |id| stored[id as usize], &bx);
    assert!((x[2] - Vec3::new(-0.4, 5.2, 1.0)).norm() < 1e-12);
}

/// Chains are found in bonds given in any order and direction, from the end with the smaller
/// id; a branched molecule, a ring and unbonded particles are no chains.
#[test]
fn linear_chains_are_found_in_a_list_of_bonds() {
    let bonds = [
        (5, 4),
        (2, 1),
        (3, 4),
        (0, 1),
        // a star 6-7, 6-8, 6-9
        (6, 7),
        (8, 6),
        (6, 9),
        // a ring 10-11-12
        (10, 11),
        (11, 12),
        (12, 10),
        // a dimer
        (14, 13),
    ];
    let chains = linear_chains(16, &bonds);
    assert_eq!(chains, [vec![0, 1, 2], vec![3, 4, 5], vec![13, 14]]);
}
