//! Linear chains of beads: how a scene's chains are laid out over particle ids and placed by
//! random walks, how chains are found again in a list of bonds, and their sizes (bond
//! lengths, end-to-end distance, radius of gyration) from positions unwrapped across the
//! periodic box by minimum-image bond vectors. Lengths in r_c's unit.

use crate::scene::molecules::ChainPlan;
use dpd_core::bonded::{Angle, Bond};
use dpd_core::rng::philox4x32_10;
use dpd_core::{PeriodicBox, Vec3};

/// A chain: the ids of its beads in order along it (each bonded to the next).
pub type Chain = Vec<u32>;

/// The chains of `plans` over consecutive ids from 0, entry after entry, with each chain's
/// plan.
pub fn layout(plans: &[ChainPlan]) -> Vec<(Chain, &ChainPlan)> {
    let mut next = 0u32;
    let mut out = Vec::new();
    for plan in plans {
        for _ in 0..plan.chains {
            let len = plan.beads.len() as u32;
            out.push(((next..next + len).collect(), plan));
            next += len;
        }
    }
    out
}

/// The type of each bead of `plans`' chains, by id, and what is left of `counts` (the
/// particles of each type) for the particles after them, which take the remaining types in
/// type order.
pub fn kinds(plans: &[ChainPlan], counts: &[usize]) -> Vec<u16> {
    let mut left = counts.to_vec();
    let mut kinds = Vec::new();
    for (_, plan) in layout(plans) {
        for &t in &plan.beads {
            left[t as usize] -= 1;
            kinds.push(t);
        }
    }
    for (t, &c) in left.iter().enumerate() {
        kinds.extend(std::iter::repeat_n(t as u16, c));
    }
    kinds
}

/// The bonds between the neighbours of every chain, and the angles at every inner bead of the
/// chains whose plan has an angle type, in chain order.
pub fn bonds_and_angles(plans: &[ChainPlan]) -> (Vec<Bond>, Vec<Angle>) {
    let (mut bonds, mut angles) = (Vec::new(), Vec::new());
    for (chain, plan) in layout(plans) {
        let kind = plan.bond;
        bonds.extend(chain.windows(2).map(|w| Bond {
            i: w[0],
            j: w[1],
            kind,
        }));
        if let Some(kind) = plan.angle {
            let angle = |w: &[u32]| Angle {
                i: w[0],
                j: w[1],
                k: w[2],
                kind,
            };
            angles.extend(chain.windows(3).map(angle));
        }
    }
    (bonds, angles)
}

/// The positions of `plans`' beads, by id: each chain a freely jointed random walk of its
/// plan's step length from a uniform point of the box, each step in a uniform direction,
/// wrapped into the box. Drawn from `seed` by Philox, one counter per bead.
pub fn random_walks(plans: &[ChainPlan], bx: &PeriodicBox, seed: u64) -> Vec<Vec3> {
    let key = [seed as u32, (seed >> 32) as u32];
    let uniforms = |id: u32| {
        let w = philox4x32_10([id, WALK_STREAM, 0, 0], key);
        w.map(|x| (f64::from(x) + 0.5) / 4_294_967_296.0)
    };
    let l = bx.lengths();
    let mut q = Vec::new();
    for (chain, plan) in layout(plans) {
        let u = uniforms(chain[0]);
        let mut x = Vec3::new(u[0] * l.x, u[1] * l.y, u[2] * l.z);
        q.push(bx.wrap(x));
        for &id in &chain[1..] {
            let u = uniforms(id);
            let (cos, phi) = (2.0 * u[0] - 1.0, std::f64::consts::TAU * u[1]);
            let sin = (1.0 - cos * cos).max(0.0).sqrt();
            x += plan.step * Vec3::new(sin * phi.cos(), sin * phi.sin(), cos);
            q.push(bx.wrap(x));
        }
    }
    q
}

/// Philox counter word that keeps the walks' numbers apart from other streams.
const WALK_STREAM: u32 = 0x7761_6c6b;

/// The linear chains among the molecules that `bonds` (pairs of ids below `particles`) make:
/// each connected set of bonded particles in which no particle has more than two bonds and
/// which is not a ring, from its end with the smaller id. Branched molecules and rings are
/// left out; particles without bonds are no chain.
pub fn linear_chains(particles: usize, bonds: &[(u32, u32)]) -> Vec<Chain> {
    let mut next: Vec<Vec<u32>> = vec![Vec::new(); particles];
    for &(i, j) in bonds {
        next[i as usize].push(j);
        next[j as usize].push(i);
    }
    let mut seen = vec![false; particles];
    let mut chains = Vec::new();
    for start in 0..particles {
        if seen[start] || next[start].is_empty() {
            continue;
        }
        // The molecule of `start`, and whether it is a path.
        let (mut stack, mut members, mut linear) = (vec![start], Vec::new(), true);
        seen[start] = true;
        while let Some(p) = stack.pop() {
            members.push(p);
            linear &= next[p].len() <= 2;
            for &o in &next[p] {
                if !seen[o as usize] {
                    seen[o as usize] = true;
                    stack.push(o as usize);
                }
            }
        }
        let bonds_in: usize = members.iter().map(|&p| next[p].len()).sum::<usize>() / 2;
        if !linear || bonds_in + 1 != members.len() {
            continue;
        }
        let Some(&end) = members.iter().filter(|&&p| next[p].len() == 1).min() else {
            continue;
        };
        let mut chain = vec![end as u32];
        let mut before = u32::MAX;
        while let Some(&o) = next[*chain.last().unwrap() as usize]
            .iter()
            .find(|&&o| o != before)
        {
            before = *chain.last().unwrap();
            chain.push(o);
        }
        chains.push(chain);
    }
    chains
}

/// The positions of `chain`'s beads made continuous: the first where it is, each next one the
/// previous plus the minimum image of their difference (`at(id)` gives a bead's position).
pub fn unwrapped(chain: &[u32], at: impl Fn(u32) -> Vec3, bx: &PeriodicBox) -> Vec<Vec3> {
    let mut out = Vec::with_capacity(chain.len());
    let mut x = at(chain[0]);
    out.push(x);
    for w in chain.windows(2) {
        x += bx.min_image(at(w[1]) - at(w[0]));
        out.push(x);
    }
    out
}

/// The squared end-to-end distance of an unwrapped chain.
pub fn end_to_end_squared(x: &[Vec3]) -> f64 {
    (x[x.len() - 1] - x[0]).norm_squared()
}

/// The squared radius of gyration of an unwrapped chain (equal bead weights): the mean squared
/// distance of its beads from their centre.
pub fn gyration_squared(x: &[Vec3]) -> f64 {
    let n = x.len() as f64;
    let centre: Vec3 = x.iter().sum::<Vec3>() / n;
    x.iter().map(|xi| (xi - centre).norm_squared()).sum::<f64>() / n
}

#[cfg(test)]
mod tests;
