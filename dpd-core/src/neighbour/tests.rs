use super::grid::{colourable, y_blocks};
use super::*;
use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::init::uniform_positions;
use crate::Vec3;

fn brute(q: &[Vec3], cut: f64, image: impl Fn(Vec3) -> Vec3) -> Vec<(u32, u32)> {
    let mut v = Vec::new();
    for i in 0..q.len() {
        for j in i + 1..q.len() {
            if image(q[i] - q[j]).norm() < cut {
                v.push((i as u32, j as u32));
            }
        }
    }
    v
}

/// Both halves of a build, as a system does them; returns the positions in cell order.
fn build(
    list: &mut VerletList,
    q: &[Vec3],
    bx: &PeriodicBox,
    shear: Option<&LeesEdwards>,
) -> Vec<Vec3> {
    list.bin(q, bx, 1.0);
    let pos = list.grid().gather(q);
    list.build(&pos, bx, shear, 1.0);
    pos
}

/// The list holds exactly the brute-force pairs, and runs of one of the independent colours
/// share no particle.
fn check_list(list: &VerletList, expected: Vec<(u32, u32)>, coloured: bool, what: &str) {
    let mut got: Vec<(u32, u32)> = list
        .candidates()
        .iter()
        .map(|&(i, j)| (i.min(j), i.max(j)))
        .collect();
    got.sort_unstable();
    assert_eq!(got, expected, "{what}");
    let g = list.groups();
    assert_eq!(g.independent > 0, coloured, "{what}");
    {
        for c in 0..g.independent {
            let mut seen = std::collections::HashMap::new();
            for k in g.colours[c]..g.colours[c + 1] {
                let run = g.runs[k as usize]..g.runs[k as usize + 1];
                for &(i, j) in list
                    .candidates()
                    .slice(run.start as usize..run.end as usize)
                {
                    for p in [i, j] {
                        assert_eq!(
                            *seen.entry(p).or_insert(k),
                            k,
                            "{what}: particle {p} in two runs of colour {c}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn colourable_counts_lose_at_most_two_layers() {
    assert_eq!(colourable(3), (3, 3));
    assert_eq!(colourable(5), (5, 5));
    assert_eq!(colourable(7), (6, 2));
    assert_eq!(colourable(20), (20, 2));
    assert_eq!(colourable(13), (12, 2));
    for n in 3..200 {
        let (count, m) = colourable(n);
        assert!(count + 2 >= n && count <= n && count.is_multiple_of(m) && m >= 2);
    }
}

/// Blocks along y: none below 16 cells, else an even number of blocks of four to seven
/// cells; the units of the sweep are each cell exactly once, colour by colour.
#[test]
fn units_cover_every_cell_once() {
    assert_eq!(y_blocks(15), 1);
    for ny in 16..200 {
        let b = y_blocks(ny);
        assert!(b >= 4 && b.is_multiple_of(2), "{ny} cells: {b} blocks");
        assert!(
            (4..=7).contains(&(ny / b)) && ny.div_ceil(b) <= 7,
            "{ny} cells: {b} blocks"
        );
    }
    for lengths in [
        [5.5, 5.5, 5.5],
        [20.0, 20.0, 20.0],
        [7.3, 17.2, 4.1],
        [2.0, 9.0, 9.0],
    ] {
        let bx = PeriodicBox::new(lengths).unwrap();
        let mut grid = CellGrid::default();
        grid.bin(&uniform_positions(&bx, 100, 1), &bx, 1.0);
        let mut cells = grid.sweep.clone();
        cells.sort_unstable();
        assert_eq!(
            cells,
            (0..grid.cells() as u32).collect::<Vec<_>>(),
            "{lengths:?}"
        );
        for (c, colour) in grid.colour_units.windows(2).enumerate() {
            let units = colour[0] as usize..colour[1] as usize;
            let cells = grid.units[units.start] as usize..grid.units[units.end] as usize;
            let wrong = grid.sweep[cells]
                .iter()
                .find(|&&k| grid.colour(k as usize) != c);
            assert_eq!(wrong, None, "{lengths:?}: colour {c}");
        }
    }
}

#[test]
fn cell_order_is_a_stable_sort_by_cell() {
    let bx = PeriodicBox::new([7.0, 9.1, 6.3]).unwrap();
    let q = uniform_positions(&bx, 500, 3);
    let mut grid = CellGrid::default();
    let order = grid.bin(&q, &bx, 1.3).to_vec();
    let mut seen = order.clone();
    seen.sort_unstable();
    assert_eq!(seen, (0..500).collect::<Vec<u32>>());
    // Binning the sorted positions again gives the identity.
    let pos = grid.gather(&q);
    assert_eq!(grid.bin(&pos, &bx, 1.3), (0..500).collect::<Vec<u32>>());
}

#[test]
fn parallel_binning_is_the_serial_stable_sort() {
    let bx = PeriodicBox::cubic(20.0).unwrap();
    let q = uniform_positions(&bx, 24_000, 4);
    let on = |threads| {
        crate::on_threads(threads, || {
            let mut grid = CellGrid::default();
            (grid.bin(&q, &bx, 1.0).to_vec(), grid.cell_start.clone())
        })
    };
    let (serial, starts) = on(1);
    // One chunk per thread; with 7 the last chunk is shorter than the others.
    for threads in [2, 3, 7] {
        assert_eq!(
            on(threads),
            (serial.clone(), starts.clone()),
            "{threads} threads"
        );
    }
    // Stable: within a cell, ascending input index.
    for c in starts.windows(2) {
        let cell = &serial[c[0] as usize..c[1] as usize];
        assert!(cell.windows(2).all(|w| w[0] < w[1]));
    }
}

#[test]
fn verlet_list_matches_brute_force_and_colours_are_disjoint() {
    // Cells of edge >= 1.3: box 5.3 has 4 x 5 x 3 (layer colours 2), 9.5 has 6 x 9 x 6 (7
    // layers rounded down to 6), the last 5 x 17 x 4 (layer colours 5, four blocks along y).
    let boxes = [
        ([2.5, 3.25, 2.25], false),
        ([4.2, 5.46, 3.78], false),
        ([5.3, 6.89, 4.77], true),
        ([6.0, 7.8, 5.4], true),
        ([7.0, 9.1, 6.3], true),
        ([9.5, 12.35, 8.55], true),
        ([7.0, 22.5, 5.5], true),
    ];
    for (lengths, coloured) in boxes {
        let (bx, l) = (PeriodicBox::new(lengths).unwrap(), lengths[0]);
        let q = uniform_positions(&bx, 400, 1);
        let mut list = VerletList::new(0.3);
        let pos = build(&mut list, &q, &bx, None);
        let expected = brute(&pos, 1.3, |d| bx.min_image(d));
        check_list(&list, expected, coloured, &format!("box {l}"));
        assert_eq!(list.groups().colours.len(), list.grid().colours() + 1);
    }
}

#[test]
fn sliding_list_matches_brute_force() {
    // Offsets aligned with the cells (0), slightly off, and arbitrary; grids of 3, 4 and
    // more cells along x (3 and 4 are where the four image cells wrap around).
    let boxes = [
        ([2.5, 3.25, 2.25], false),
        ([4.2, 4.5, 4.5], true),
        ([5.3, 6.9, 4.8], true),
        ([7.0, 9.1, 6.3], true),
        ([9.5, 12.35, 8.55], true),
        ([7.0, 22.5, 5.5], true),
    ];
    for (lengths, coloured) in boxes {
        let bx = PeriodicBox::new(lengths).unwrap();
        let l = lengths[0];
        let q = uniform_positions(&bx, 400, 2);
        for offset in [0.0, 1e-9, 0.37 * l, 0.999 * l] {
            let le = LeesEdwards::restore(0.3, offset, 0.0, &bx).unwrap();
            let mut list = VerletList::new(0.3);
            let pos = build(&mut list, &q, &bx, Some(&le));
            let expected = brute(&pos, 1.3, |d| le.min_image(&bx, d).0);
            check_list(
                &list,
                expected,
                coloured,
                &format!("box {l}, offset {offset}"),
            );
            let colours = list.groups().colours.len() - 1;
            assert_eq!(colours, list.grid().colours() + usize::from(offset != 0.0));
        }
    }
}

#[test]
fn rebuilds_only_after_half_skin() {
    let bx = PeriodicBox::cubic(5.0).unwrap();
    let mut q = vec![Vec3::new(1.0, 1.0, 1.0), Vec3::new(2.0, 1.0, 1.0)];
    let mut list = VerletList::new(0.4);
    assert!(list.needs_rebuild(&q, &bx, None));
    build(&mut list, &q, &bx, None);
    q[0].x += 0.19;
    assert!(!list.needs_rebuild(&q, &bx, None));
    q[0].x += 0.02;
    assert!(list.needs_rebuild(&q, &bx, None));
}

#[test]
fn without_skin_rebuilds_when_positions_change() {
    let bx = PeriodicBox::cubic(5.0).unwrap();
    let q = vec![Vec3::new(1.0, 1.0, 1.0), Vec3::new(2.0, 1.0, 1.0)];
    let mut list = VerletList::new(0.0);
    build(&mut list, &q, &bx, None);
    assert!(!list.needs_rebuild(&q, &bx, None));
    assert!(list.candidates().is_empty() && list.reference().is_empty());
    list.positions_changed();
    assert!(list.needs_rebuild(&q, &bx, None));
}

#[test]
fn sliding_images_shorten_the_rebuild_interval() {
    // After the images slid by 0.1, the skin 0.4 leaves (0.4 - 0.3) / 2 = 0.05 of
    // displacement.
    let bx = PeriodicBox::cubic(5.0).unwrap();
    let mut le = LeesEdwards::new(0.1).unwrap();
    let mut q = vec![Vec3::new(1.0, 1.0, 1.0), Vec3::new(2.0, 1.0, 1.0)];
    let mut list = VerletList::new(0.4);
    build(&mut list, &q, &bx, Some(&le));
    le.advance(&bx, 0.2);
    q[0].x += 0.04;
    assert!(!list.needs_rebuild(&q, &bx, Some(&le)));
    q[0].x += 0.02;
    assert!(list.needs_rebuild(&q, &bx, Some(&le)));
}
