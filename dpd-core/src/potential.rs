//! The soft repulsion of DPD, the model's one conservative interaction (algorithms.md
//! section 1): `phi(r) = (a r_c / 2) (1 - r/r_c)^2` for `r < r_c`, zero beyond.
//!
//! Every loop that needs the conservative pair force, the potential energy, its Laplacian or the
//! pair virial takes it from [`Soft`], as a function of the pair weight `w = 1 - r/r_c` that
//! [`crate::pairs::Pair`] carries, so the formula is written once. The expressions are kept in
//! the order the loops used before they were gathered here, so that every sum is bitwise the
//! same.

/// The soft repulsion of one pair: strength `a` (the `a_ij` of the pair's types, energy per
/// length) and cutoff `r_c`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Soft {
    a: f64,
    rc: f64,
}

impl Soft {
    /// The repulsion of strength `a` with cutoff `rc`.
    #[inline(always)]
    pub fn new(a: f64, rc: f64) -> Self {
        Soft { a, rc }
    }

    /// The force along `e_ij` (from j to i) at weight `w`: `f = -phi'(r) = a w`, so that
    /// `F^C_ij = f e_ij` acts on i and `-F^C_ij` on j.
    #[inline(always)]
    pub fn force(self, w: f64) -> f64 {
        self.a * w
    }

    /// The pair's potential energy at weight `w`: `phi = (a r_c / 2) w^2`.
    #[inline(always)]
    pub fn energy(self, w: f64) -> f64 {
        0.5 * self.a * self.rc * w * w
    }

    /// The pair's share of `sum_i lap_i U` at weight `w`, both particles' Laplacians of `phi`:
    /// in three dimensions `lap phi = phi'' + 2 phi' / r = a / r_c - 2 a w / r`, counted for i
    /// and for j. Diverges as `r -> 0`.
    #[inline(always)]
    pub fn laplacian(self, w: f64) -> f64 {
        let r = self.distance(w);
        2.0 * (self.a / self.rc - 2.0 * self.a * w / r)
    }

    /// The pair virial `r f` at weight `w` (`q_ij . F^C_ij`; its tensor is this times
    /// `e_ij (x) e_ij`).
    #[inline(always)]
    pub fn virial(self, w: f64) -> f64 {
        self.distance(w) * self.a * w
    }

    /// The distance `r = r_c (1 - w)` of weight `w`.
    #[inline(always)]
    fn distance(self, w: f64) -> f64 {
        self.rc * (1.0 - w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Vec3;

    /// A repulsion with a cutoff other than 1, so that a misplaced `r_c` shows.
    const SOFT: Soft = Soft { a: 18.5, rc: 1.3 };

    fn weight(r: f64) -> f64 {
        1.0 - r / SOFT.rc
    }

    /// `phi(|x|)`, zero beyond the cutoff.
    fn phi(x: Vec3) -> f64 {
        let r = x.norm();
        if r < SOFT.rc {
            SOFT.energy(weight(r))
        } else {
            0.0
        }
    }

    /// Distances across the range, away from 0 (where the Laplacian diverges) and from the
    /// cutoff (where `phi''` jumps and a central difference straddles it).
    fn distances() -> impl Iterator<Item = f64> {
        (1..40).map(|k| 0.1 + 1.15 * f64::from(k) / 40.0)
    }

    /// Force against `-phi'(r)` by a central difference of step `1e-5`: truncation error
    /// `phi''' d^2 / 6 = 0` (phi is quadratic in r), rounding about `1e-16 phi / 1e-5 ~ 1e-10`,
    /// so a relative tolerance of `1e-8` holds for the right force and fails for a factor or
    /// sign error.
    #[test]
    fn the_force_is_minus_the_derivative_of_the_energy() {
        let d = 1e-5;
        for r in distances() {
            let numeric = -(SOFT.energy(weight(r + d)) - SOFT.energy(weight(r - d))) / (2.0 * d);
            let f = SOFT.force(weight(r));
            assert!(
                (f - numeric).abs() <= 1e-8 * f.abs(),
                "r = {r}: {f} vs {numeric}"
            );
        }
    }

    /// Laplacian against the seven-point finite-difference Laplacian of `phi(|x|)` in three
    /// dimensions, counted for both particles, at points off the axes. Step `1e-4`: truncation
    /// `~ d^2 phi'''' / 12` (of the radial function's expansion, `~ a / r^3 d^2 ~ 1e-6` at the
    /// smallest r) and rounding `~ 1e-16 phi / d^2 ~ 1e-7`: a tolerance of `1e-5` relative
    /// (with `1e-5` absolute near the zero of the Laplacian) passes, while a missing `2 phi'/r`
    /// term or factor 2 is off by more than 10 %.
    #[test]
    fn the_laplacian_is_that_of_the_energy_for_both_particles() {
        let d = 1e-4;
        let direction = Vec3::new(0.48, -0.6, 0.64);
        for r in distances() {
            let x = r * direction;
            let mut numeric = -6.0 * phi(x);
            for axis in 0..3 {
                let step = d * Vec3::ith(axis, 1.0);
                numeric += phi(x + step) + phi(x - step);
            }
            let numeric = 2.0 * numeric / (d * d);
            let lap = SOFT.laplacian(weight(r));
            assert!(
                (lap - numeric).abs() <= 1e-5 * (1.0 + lap.abs()),
                "r = {r}: {lap} vs {numeric}"
            );
        }
    }

    /// The virial is distance times force, and energy and force vanish at the cutoff (the
    /// potential is continuous there, and so is the force).
    #[test]
    fn the_virial_is_distance_times_force_and_all_vanish_at_the_cutoff() {
        for r in distances() {
            let w = weight(r);
            let (v, f) = (SOFT.virial(w), SOFT.force(w));
            assert!(
                (v - r * f).abs() <= 1e-14 * v.abs(),
                "r = {r}: {v} vs {}",
                r * f
            );
        }
        assert_eq!(
            (SOFT.energy(0.0), SOFT.force(0.0), SOFT.virial(0.0)),
            (0.0, 0.0, 0.0)
        );
    }
}
