//! Planar walls across z for channel flows (algorithms.md section 8): Couette flow between
//! moving walls and Poiseuille flow driven by a body force.
//!
//! A wall is a slab of frozen particles (inverse mass 0: no force moves them) outside the
//! channel `lower <= z < upper`. Frozen particles interact with the fluid through all three
//! pair forces; the dissipative and random forces see them moving at their wall's velocity
//! (along x), which enters a pair as its velocity shift
//! ([`crate::pairs::PairTable::shifts`]); pairs of two frozen particles are left out. The box stays periodic along z: the two wall slabs together
//! must be at least `r_c` thick, so that the fluid never sees itself across them, and nothing
//! in the neighbour search changes.
//!
//! Reflection rule: a fluid particle that a drift carries out of the channel is put back at
//! the mirror image of its position in the wall plane, with bounce-back velocity
//! `v -> 2 u_wall - v` (all components reversed relative to the wall, the no-slip rule).

use crate::boundary::PeriodicBox;
use crate::error::ParamError;
use crate::Vec3;

/// The channel `lower <= z <= upper` and the x-velocities of its two walls.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Walls {
    lower: f64,
    upper: f64,
    velocity: [f64; 2],
}

impl Walls {
    /// Walls at `z = lower` and `z = upper` moving along x at `velocity = [lower, upper]`.
    pub fn new(lower: f64, upper: f64, velocity: [f64; 2]) -> Result<Self, ParamError> {
        if !(lower.is_finite() && upper.is_finite() && lower < upper) {
            return Err(ParamError::new(
                "walls",
                format!("z = {lower} .. {upper}"),
                "needs finite wall planes with lower < upper",
            ));
        }
        for (name, v) in ["walls.velocity[0]", "walls.velocity[1]"]
            .iter()
            .zip(velocity)
        {
            if !v.is_finite() {
                return Err(ParamError::new(*name, v, "must be finite"));
            }
        }
        Ok(Walls {
            lower,
            upper,
            velocity,
        })
    }

    pub fn lower(&self) -> f64 {
        self.lower
    }
    pub fn upper(&self) -> f64 {
        self.upper
    }
    /// x-velocities of the lower and upper wall.
    pub fn velocity(&self) -> [f64; 2] {
        self.velocity
    }

    /// Check the walls against the box and cutoff: the channel lies in `[0, L_z]` and the wall
    /// slabs are at least `rc` thick together.
    pub(crate) fn check(&self, bx: &PeriodicBox, rc: f64) -> Result<(), ParamError> {
        let lz = bx.lengths().z;
        if self.lower < 0.0 || self.upper > lz {
            return Err(ParamError::new(
                "walls",
                format!("z = {} .. {}", self.lower, self.upper),
                format!("the channel must lie inside the box, 0 <= z <= L_z = {lz}"),
            ));
        }
        let slab = lz - (self.upper - self.lower);
        if slab < rc {
            return Err(ParamError::new(
                "walls",
                format!("z = {} .. {}", self.lower, self.upper),
                format!(
                    "the wall slabs are {slab} thick together; they need at least r_c = {rc} so \
                     that the fluid does not interact with itself across them"
                ),
            ));
        }
        Ok(())
    }

    /// Whether `z` is inside the channel (planes included).
    pub fn contains(&self, z: f64) -> bool {
        (self.lower..=self.upper).contains(&z)
    }

    /// x-velocity of a frozen particle at height `z` (outside the channel): that of the wall
    /// whose slab holds it (above `upper`: the upper wall).
    pub(crate) fn frozen_velocity(&self, z: f64) -> f64 {
        if z > self.upper {
            self.velocity[1]
        } else {
            self.velocity[0]
        }
    }

    /// Apply the reflection rule to a fluid particle of mass `m` after a drift.
    #[inline(always)]
    pub(crate) fn reflect(&self, q: &mut Vec3, p: &mut Vec3, m: f64) {
        let (plane, u) = if q.z < self.lower {
            (self.lower, self.velocity[0])
        } else if q.z > self.upper {
            (self.upper, self.velocity[1])
        } else {
            return;
        };
        q.z = 2.0 * plane - q.z;
        *p = 2.0 * m * Vec3::new(u, 0.0, 0.0) - *p;
    }
}

/// Walls with the particles frozen in them, as a system holds them.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct FrozenWalls {
    pub(crate) walls: Walls,
    /// Whether each particle is frozen.
    pub(crate) frozen: Vec<bool>,
    /// x-velocity each particle has as far as pair forces go when frozen (0 when mobile).
    pub(crate) velocity_x: Vec<f64>,
}

impl FrozenWalls {
    /// Check `frozen` against `walls` and positions `q`: frozen particles lie in the wall
    /// slabs, mobile ones in the channel.
    pub(crate) fn new(walls: Walls, frozen: Vec<bool>, q: &[Vec3]) -> Result<Self, ParamError> {
        for (i, (x, &f)) in q.iter().zip(&frozen).enumerate() {
            if f == walls.contains(x.z) {
                let (what, place) = if f {
                    ("frozen", "in a wall slab (z < lower or z > upper)")
                } else {
                    ("mobile", "in the channel (lower <= z <= upper)")
                };
                return Err(ParamError::new(
                    format!("positions[{i}]"),
                    format!("{x:?}"),
                    format!(
                        "a {what} particle must lie {place}; walls at z = {} and {}",
                        walls.lower, walls.upper
                    ),
                ));
            }
        }
        let velocity_x = q
            .iter()
            .zip(&frozen)
            .map(|(x, &f)| if f { walls.frozen_velocity(x.z) } else { 0.0 })
            .collect();
        Ok(FrozenWalls {
            walls,
            frozen,
            velocity_x,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reflection_mirrors_and_bounces_back() {
        let w = Walls::new(1.0, 9.0, [-2.0, 3.0]).unwrap();
        let (mut q, mut p) = (Vec3::new(0.5, 2.0, 9.25), Vec3::new(1.0, 2.0, 4.0));
        w.reflect(&mut q, &mut p, 2.0);
        assert_eq!(q, Vec3::new(0.5, 2.0, 8.75));
        assert_eq!(p, Vec3::new(11.0, -2.0, -4.0));
        let (mut q, mut p) = (Vec3::new(0.5, 2.0, 0.75), Vec3::new(1.0, 0.0, -1.0));
        w.reflect(&mut q, &mut p, 1.0);
        assert_eq!((q.z, p), (1.25, Vec3::new(-5.0, 0.0, 1.0)));
        assert_eq!(w.frozen_velocity(9.5), 3.0);
        assert_eq!(w.frozen_velocity(0.5), -2.0);
    }

    #[test]
    fn bad_walls_are_named() {
        let bx = PeriodicBox::new([4.0, 4.0, 10.0]).unwrap();
        assert_eq!(Walls::new(2.0, 1.0, [0.0; 2]).unwrap_err().field, "walls");
        assert_eq!(
            Walls::new(0.0, 1.0, [f64::NAN, 0.0]).unwrap_err().field,
            "walls.velocity[0]"
        );
        let thin = Walls::new(0.5, 9.8, [0.0; 2]).unwrap();
        assert!(thin.check(&bx, 1.0).unwrap_err().allowed.contains("r_c"));
        assert!(Walls::new(1.0, 9.0, [0.0; 2])
            .unwrap()
            .check(&bx, 1.0)
            .is_ok());
    }
}
