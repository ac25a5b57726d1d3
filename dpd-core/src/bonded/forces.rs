//! The loops over a located topology: bonded forces and energy at given positions.

use super::{Angle, Bond, Located};
use crate::boundary::{LeesEdwards, PeriodicBox};
use crate::{Tensor, Vec3};

/// Where the particles are: positions in storage order, wrapped into the box, and the
/// boundaries that give each bond vector its minimum image.
#[derive(Clone, Copy)]
pub(crate) struct Frame<'a> {
    pub q: &'a [Vec3],
    pub bx: &'a PeriodicBox,
    pub shear: Option<&'a LeesEdwards>,
}

impl Frame<'_> {
    /// `q_i - q_j` under minimum image (storage indices).
    #[inline(always)]
    fn delta(&self, i: u32, j: u32) -> Vec3 {
        self.image(self.q[i as usize] - self.q[j as usize])
    }

    /// The minimum image of the difference `d` of two positions in the box.
    #[inline(always)]
    fn image(&self, d: Vec3) -> Vec3 {
        match self.shear {
            None => self.bx.near_image(d),
            Some(le) => le.min_image(self.bx, d).0,
        }
    }
}

/// A bond found at or beyond its reach (a FENE bond at `R0`) by a force evaluation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Overstretch {
    /// The bond's index in the topology.
    pub bond: usize,
    /// Its length.
    pub r: f64,
}

/// How many bonds ahead [`Located::each_bond`] fetches the second particle's position.
const AHEAD: usize = 16;

/// Ask the CPU to bring `x` into its caches (a hint: no effect on results, none off x86_64).
#[inline(always)]
fn prefetch<T>(x: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // SAFETY: a prefetch reads nothing and cannot fault; `x` is a valid reference anyway.
        unsafe { _mm_prefetch::<_MM_HINT_T0>((x as *const T).cast()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = x;
}

/// One bond as [`Located::each_bond`] visits it: its vector `d = q_i - q_j` of squared length
/// `r2`, the force on `i`.
struct BondTerm<'a> {
    bond: &'a Bond,
    d: Vec3,
    r2: f64,
    force: Vec3,
    /// The second particle of the bond [`AHEAD`] bonds later, if any: what a visit writing per
    /// particle may fetch early.
    later: Option<u32>,
}

/// One angle as [`Located::each_angle`] visits it: its arms `q_i - q_j`, `q_k - q_j` and the
/// forces on `i` and `k`.
struct AngleTerm<'a> {
    angle: &'a Angle,
    arms: [Vec3; 2],
    forces: [Vec3; 2],
}

/// One angle's geometry: the arms `a = q_i - q_j`, `b = q_k - q_j` from the vertex, `cos
/// theta` and the gradients of `cos theta` with respect to `q_i` and `q_k`.
struct Bend {
    c: f64,
    dc_di: Vec3,
    dc_dk: Vec3,
    /// `|a|^2`, `|b|^2`.
    aa: f64,
    bb: f64,
}

impl Bend {
    /// `sum_p |grad_p cos theta|^2` over the three particles (`grad_j = -grad_i - grad_k`).
    fn gradient_squared(&self) -> f64 {
        let (gi, gk) = (self.dc_di, self.dc_dk);
        gi.norm_squared() + gk.norm_squared() + (gi + gk).norm_squared()
    }

    /// `sum_p lap_p cos theta` over the three particles: `lap_i c = -2c / |a|^2` (`c` is the
    /// cosine of the angle between `a` and a fixed direction), `lap_k c = -2c / |b|^2`, and
    /// `lap_j c = lap_i c + lap_k c + 2 (1 + c^2) / (|a| |b|)` (the mixed second derivatives
    /// `sum_x d^2 c / da_x db_x = (1 + c^2) / (|a| |b|)`).
    fn laplacian(&self) -> f64 {
        let c = self.c;
        -4.0 * c / self.aa - 4.0 * c / self.bb + 2.0 * (1.0 + c * c) / (self.aa * self.bb).sqrt()
    }
}

/// The bonded terms of the thermodynamic observables at one configuration.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct BondedSums {
    /// Bonded potential energy.
    pub energy: f64,
    /// `sum_i lap_i` of the bonded energy (the configurational temperature's denominator).
    pub laplacian: f64,
    /// `sum_bonds q_ij . F_ij`, the bonds' share of the virial. Angles add nothing: their
    /// energy depends on the angle alone, unchanged when every length is scaled.
    pub virial: f64,
}

impl Bend {
    #[inline]
    fn new(a: Vec3, b: Vec3) -> Bend {
        let (aa, bb) = (a.norm_squared(), b.norm_squared());
        let inv_ab = 1.0 / (aa * bb).sqrt();
        let c = a.dot(&b) * inv_ab;
        Bend {
            c,
            dc_di: b * inv_ab - a * (c / aa),
            dc_dk: a * inv_ab - b * (c / bb),
            aa,
            bb,
        }
    }
}

impl Located {
    /// Visit every bond with its geometry and force. The boundary is resolved once, not per
    /// bond: each loop is compiled for its own.
    #[inline(always)]
    fn each_bond(&self, frame: Frame, visit: impl FnMut(BondTerm)) {
        match frame.shear {
            None => self.each_bond_imaged(frame.q, |d| frame.bx.near_image(d), visit),
            Some(le) => self.each_bond_imaged(frame.q, |d| le.min_image(frame.bx, d).0, visit),
        }
    }

    /// [`Located::each_bond`] with the bond vectors imaged by `image`.
    ///
    /// The bonds are in the storage order of their first particle, but the second lies up to a
    /// layer of cells away: its position, read at random, stalled the loop (perf put 43 % of
    /// the loop's samples on that load). It is fetched into the cache [`AHEAD`] bonds early.
    #[inline(always)]
    fn each_bond_imaged(
        &self,
        q: &[Vec3],
        image: impl Fn(Vec3) -> Vec3,
        mut visit: impl FnMut(BondTerm),
    ) {
        let styles = self.topology.bond_types();
        for (n, b) in self.bonds.iter().enumerate() {
            let later = self.bonds.get(n + AHEAD).map(|later| later.j);
            if let Some(j) = later {
                prefetch(&q[j as usize]);
            }
            let d = image(q[b.i as usize] - q[b.j as usize]);
            let r2 = d.norm_squared();
            let force = styles[b.kind as usize].force_over_r(r2) * d;
            visit(BondTerm {
                bond: b,
                d,
                r2,
                force,
                later,
            });
        }
    }

    /// Visit every angle with its geometry and forces.
    #[inline(always)]
    fn each_angle(&self, frame: Frame, mut visit: impl FnMut(AngleTerm)) {
        let styles = self.topology.angle_types();
        for a in &self.angles {
            let arms = [frame.delta(a.i, a.j), frame.delta(a.k, a.j)];
            let bend = Bend::new(arms[0], arms[1]);
            let slope = styles[a.kind as usize].slope(bend.c);
            let forces = [-slope * bend.dc_di, -slope * bend.dc_dk];
            visit(AngleTerm {
                angle: a,
                arms,
                forces,
            });
        }
    }

    /// The bonded forces at `frame` into `out` (one per particle, storage order); the
    /// overstretched bond of lowest index, if any (its force is then meaningless).
    pub(crate) fn forces(&self, frame: Frame, out: &mut Vec<Vec3>) -> Option<Overstretch> {
        out.clear();
        out.resize(frame.q.len(), Vec3::zeros());
        let styles = self.topology.bond_types();
        let mut stretched = false;
        // Inlined into both loops of `each_bond` (one per boundary).
        self.each_bond(
            frame,
            #[inline(always)]
            |t| {
                if let Some(j) = t.later {
                    prefetch(&out[j as usize]);
                }
                stretched |= styles[t.bond.kind as usize].overstretched(t.r2);
                out[t.bond.i as usize] += t.force;
                out[t.bond.j as usize] -= t.force;
            },
        );
        self.each_angle(frame, |t| {
            let ([fi, fk], a) = (t.forces, t.angle);
            out[a.i as usize] += fi;
            out[a.k as usize] += fk;
            out[a.j as usize] -= fi + fk;
        });
        // Which bond, looked for only when some bond is (a blow-up): the loop stays short.
        if stretched {
            self.overstretch(frame)
        } else {
            None
        }
    }

    /// The bonded virial tensor `sum_bonds d (x) F + sum_angles (a (x) F_i + b (x) F_k)` at
    /// `frame` (row index: position component), the bonded share of the stress's
    /// conservative part; its trace is [`BondedSums::virial`] (an angle's trace is 0).
    pub(crate) fn virial_tensor(&self, frame: Frame) -> Tensor {
        let mut w = Tensor::zeros();
        self.each_bond(frame, |t| w += t.d * t.force.transpose());
        self.each_angle(frame, |t| {
            let ([a, b], [fi, fk]) = (t.arms, t.forces);
            w += a * fi.transpose() + b * fk.transpose();
        });
        w
    }

    /// The bond of lowest index at or beyond its reach at `frame`, if any.
    pub(crate) fn overstretch(&self, frame: Frame) -> Option<Overstretch> {
        let styles = self.topology.bond_types();
        let bonds = self.bonds.iter().zip(&self.bond_index);
        let over = bonds.filter_map(|(b, &n)| {
            let r2 = frame.delta(b.i, b.j).norm_squared();
            let over = styles[b.kind as usize].overstretched(r2);
            over.then(|| Overstretch {
                bond: n as usize,
                r: r2.sqrt(),
            })
        });
        over.min_by_key(|o| o.bond)
    }

    /// The bonded energy, Laplacian and virial at `frame` (NaN with an overstretched FENE
    /// bond).
    pub(crate) fn sums(&self, frame: Frame) -> BondedSums {
        let mut sums = BondedSums::default();
        let styles = self.topology.bond_types();
        for b in &self.bonds {
            let style = &styles[b.kind as usize];
            let r2 = frame.delta(b.i, b.j).norm_squared();
            sums.energy += style.energy(r2.sqrt());
            sums.laplacian += style.laplacian(r2);
            sums.virial += style.force_over_r(r2) * r2;
        }
        let styles = self.topology.angle_types();
        for a in &self.angles {
            let style = &styles[a.kind as usize];
            let bend = Bend::new(frame.delta(a.i, a.j), frame.delta(a.k, a.j));
            sums.energy += style.energy(bend.c);
            sums.laplacian += style.curvature(bend.c) * bend.gradient_squared()
                + style.slope(bend.c) * bend.laplacian();
        }
        sums
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bonded::{Angle, AngleStyle, Bond, BondStyle, Topology};

    fn frame<'a>(q: &'a [Vec3], bx: &'a PeriodicBox) -> Frame<'a> {
        Frame { q, bx, shear: None }
    }

    /// The bonded energy at `at` with particle `i` moved by `h` along axis `c`.
    fn energy_moved(located: &Located, at: Frame, i: usize, c: usize, h: f64) -> f64 {
        let mut q = at.q.to_vec();
        q[i][c] += h;
        located.sums(Frame { q: &q, ..at }).energy
    }

    /// Five beads straddling the corner of a small periodic box (so that bond vectors need
    /// their minimum image), every bond and angle style.
    fn set_up() -> (Located, PeriodicBox, Vec<Vec3>) {
        let bx = PeriodicBox::new([3.0, 3.5, 4.0]).unwrap();
        let q = [
            Vec3::new(2.9, 0.2, 3.8),
            Vec3::new(0.3, 0.1, 0.2),
            Vec3::new(0.6, 3.2, 0.5),
            Vec3::new(1.1, 3.4, 0.1),
            Vec3::new(1.3, 0.3, 3.7),
        ];
        let mut t = Topology::builder(5);
        t.bond_types = vec![
            BondStyle::Harmonic { k: 2.0, r0: 0.0 },
            BondStyle::Harmonic { k: 50.0, r0: 0.7 },
            BondStyle::Fene {
                k: 30.0,
                r_max: 1.5,
            },
        ];
        let bond = |i, j, kind| Bond { i, j, kind };
        t.bonds = vec![bond(0, 1, 0), bond(1, 2, 1), bond(2, 3, 2), bond(3, 4, 1)];
        t.angle_types = vec![
            AngleStyle::Cosine { k: 3.0 },
            AngleStyle::CosineSquared {
                k: 7.0,
                theta0: 2.0,
            },
        ];
        let angle = |i, j, k, kind| Angle { i, j, k, kind };
        t.angles = vec![angle(0, 1, 2, 0), angle(1, 2, 3, 1), angle(2, 3, 4, 1)];
        // Stored in another order than the ids.
        let ids = [3, 0, 4, 1, 2];
        let q = ids.iter().map(|&i| q[i as usize]).collect();
        (Located::new(t.build().unwrap(), &ids), bx, q)
    }

    /// Every force component is minus the derivative of the energy, by central differences
    /// with step 1e-6 (truncation error ~1e-12 times the third derivative, rounding ~1e-10):
    /// agreement to 1e-6 relative to the largest force, in the periodic box and across
    /// Lees-Edwards boundaries slid by a third of the box. The forces sum to zero to rounding.
    #[test]
    fn forces_are_minus_the_gradient_of_the_energy() {
        let (located, bx, q) = set_up();
        let mut sheared = LeesEdwards::new(0.5).unwrap();
        sheared.advance(&bx, 2.0 / 3.5);
        for shear in [None, Some(&sheared)] {
            let at = Frame {
                q: &q,
                bx: &bx,
                shear,
            };
            let mut f = Vec::new();
            assert_eq!(located.forces(at, &mut f), None);
            let scale = f.iter().map(|f: &Vec3| f.amax()).fold(0.0, f64::max);
            assert!(scale > 1.0, "{scale}");
            let h = 1e-6;
            for (i, f) in f.iter().enumerate() {
                for (c, &f) in f.iter().enumerate() {
                    let moved = |s| energy_moved(&located, at, i, c, s * h);
                    let numeric = -(moved(1.0) - moved(-1.0)) / (2.0 * h);
                    assert!(
                        (numeric - f).abs() < 1e-6 * scale,
                        "{shear:?}: particle {i} axis {c}: {numeric} vs {f}"
                    );
                }
            }
            let total: Vec3 = f.iter().sum();
            assert!(total.amax() < 1e-13 * scale, "{total:?}");
        }
    }

    /// The Laplacian sum is the trace of the energy's Hessian, by central second differences
    /// with step 1e-4 (truncation ~1e-8 times the fourth derivative, rounding ~1e-16 U / h^2 ~
    /// 1e-6): agreement to 1e-5 relative. The virial is `-dU/de` under the scaling of every
    /// length by `1 + e` (box and positions), by central differences with step 1e-6.
    #[test]
    fn laplacian_and_virial_are_derivatives_of_the_energy() {
        let (located, bx, q) = set_up();
        let sums = located.sums(frame(&q, &bx));
        let u = sums.energy;
        let h = 1e-4;
        let mut trace = 0.0;
        for i in 0..q.len() {
            for c in 0..3 {
                let moved = |s| energy_moved(&located, frame(&q, &bx), i, c, s * h);
                trace += (moved(1.0) + moved(-1.0) - 2.0 * u) / (h * h);
            }
        }
        assert!(
            (trace - sums.laplacian).abs() < 1e-5 * sums.laplacian.abs(),
            "{trace} vs {}",
            sums.laplacian
        );
        let e = 1e-6;
        let scaled = |s: f64| {
            let f = 1.0 + s * e;
            let bx = PeriodicBox::new((f * bx.lengths()).into()).unwrap();
            let q: Vec<Vec3> = q.iter().map(|x| f * x).collect();
            located.sums(frame(&q, &bx)).energy
        };
        let virial = -(scaled(1.0) - scaled(-1.0)) / (2.0 * e);
        assert!(
            (virial - sums.virial).abs() < 1e-6 * sums.virial.abs(),
            "{virial} vs {}",
            sums.virial
        );
    }

    /// The virial tensor is `-dU/de` under the deformation `u -> (1 + e E) u`, `E = e_row
    /// e_col^T`, of the molecule's contiguous (unwrapped) coordinates, for each of the nine
    /// components, by central differences with step 1e-6 (to 1e-6 of the largest component);
    /// its trace is the scalar virial.
    #[test]
    fn virial_tensor_is_the_strain_derivative_of_the_energy() {
        let (located, bx, q) = set_up();
        let origin = q[0];
        let u: Vec<Vec3> = q
            .iter()
            .map(|x| origin + bx.min_image(x - origin))
            .collect();
        let w = located.virial_tensor(frame(&u, &bx));
        let scale = w.amax();
        for row in 0..3 {
            for col in 0..3 {
                let strained = |e: f64| {
                    let moved: Vec<Vec3> = u
                        .iter()
                        .map(|x| {
                            let mut y = *x;
                            y[row] += e * x[col];
                            y
                        })
                        .collect();
                    located.sums(frame(&moved, &bx)).energy
                };
                let numeric = -(strained(1e-6) - strained(-1e-6)) / 2e-6;
                assert!(
                    (numeric - w[(col, row)]).abs() < 1e-6 * scale,
                    "({row}, {col}): {numeric} vs {}",
                    w[(col, row)]
                );
            }
        }
        let sums = located.sums(frame(&u, &bx));
        assert!((w.trace() - sums.virial).abs() < 1e-12 * scale);
    }

    /// Known values: a harmonic bond K (r - r0)^2, FENE at half its reach, the angle energies
    /// of a right angle.
    #[test]
    fn energies_follow_lammps_conventions() {
        let harmonic = BondStyle::Harmonic { k: 50.0, r0: 0.7 };
        assert!((harmonic.energy(0.9) - 50.0 * 0.04).abs() < 1e-13);
        assert!((harmonic.force_over_r(0.81) * 0.9 + 2.0 * 50.0 * 0.2).abs() < 1e-12);
        let fene = BondStyle::Fene {
            k: 30.0,
            r_max: 1.5,
        };
        let expected = -0.5 * 30.0 * 2.25 * (0.75f64).ln();
        assert!((fene.energy(0.75) - expected).abs() < 1e-13);
        assert!(fene.overstretched(2.25) && !fene.overstretched(2.2499));
        let c = (std::f64::consts::FRAC_PI_2).cos();
        assert!((AngleStyle::Cosine { k: 3.0 }.energy(c) - 3.0).abs() < 1e-15);
        let squared = AngleStyle::CosineSquared {
            k: 7.0,
            theta0: std::f64::consts::PI,
        };
        assert!((squared.energy(c) - 7.0).abs() < 1e-15);
        // Groot-Warren's spring (K = 2, r0 = 0): 2 * 3 * 2K = 24 for the two beads at any r.
        let gw = BondStyle::Harmonic { k: 2.0, r0: 0.0 };
        assert_eq!((gw.laplacian(0.0), gw.laplacian(0.49)), (24.0, 24.0));
    }
}
