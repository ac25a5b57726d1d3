//! Periodic orthorhombic simulation box with minimum-image convention.

use crate::error::{positive, ParamError};
use crate::Vec3;
use serde::{Deserialize, Serialize};

/// Periodic orthorhombic box `[0, Lx) x [0, Ly) x [0, Lz)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "[f64; 3]", into = "[f64; 3]")]
pub struct PeriodicBox {
    lengths: Vec3,
    inv: Vec3,
}

impl PeriodicBox {
    /// A box with edge lengths `lengths`; each must be finite and > 0.
    pub fn new(lengths: [f64; 3]) -> Result<Self, ParamError> {
        for (k, axis) in ["box.x", "box.y", "box.z"].iter().enumerate() {
            positive(axis, lengths[k])?;
        }
        let l = Vec3::from(lengths);
        Ok(PeriodicBox {
            lengths: l,
            inv: l.map(|x| 1.0 / x),
        })
    }

    /// A cube of edge `length`.
    pub fn cubic(length: f64) -> Result<Self, ParamError> {
        Self::new([length; 3])
    }

    pub fn lengths(&self) -> Vec3 {
        self.lengths
    }

    pub fn volume(&self) -> f64 {
        self.lengths.x * self.lengths.y * self.lengths.z
    }

    /// The shortest edge.
    pub fn min_length(&self) -> f64 {
        self.lengths.min()
    }

    /// The periodic image of `d` closest to the origin.
    ///
    /// Exact for the difference of two wrapped positions (`|d_k| < L_k`), which is what the
    /// core always passes: one conditional shift per axis, no rounding call (on baseline
    /// x86-64, `f64::round` is a library call and dominated neighbour search). Larger `d`
    /// take the general path.
    #[inline(always)]
    pub fn min_image(&self, d: Vec3) -> Vec3 {
        Vec3::new(
            image1(d.x, self.lengths.x, self.inv.x),
            image1(d.y, self.lengths.y, self.inv.y),
            image1(d.z, self.lengths.z, self.inv.z),
        )
    }

    /// `q` mapped into `[0, L)` on every axis. Non-finite input stays non-finite.
    #[inline(always)]
    pub fn wrap(&self, q: Vec3) -> Vec3 {
        Vec3::new(
            wrap1(q.x, self.lengths.x),
            wrap1(q.y, self.lengths.y),
            wrap1(q.z, self.lengths.z),
        )
    }
}

#[inline(always)]
fn image1(d: f64, l: f64, inv: f64) -> f64 {
    let half = 0.5 * l;
    let e = if d > half {
        d - l
    } else if d < -half {
        d + l
    } else {
        d
    };
    if e.abs() <= half {
        e
    } else {
        d - l * (d * inv).round()
    }
}

#[inline(always)]
fn wrap1(x: f64, l: f64) -> f64 {
    let y = if x >= l {
        x - l
    } else if x < 0.0 {
        x + l
    } else {
        return x;
    };
    if (0.0..l).contains(&y) {
        y
    } else {
        // Far outside (or rounding landed exactly on l): the general, slower path.
        let z = x.rem_euclid(l);
        if z < l {
            z
        } else {
            0.0
        }
    }
}

impl TryFrom<[f64; 3]> for PeriodicBox {
    type Error = ParamError;
    fn try_from(l: [f64; 3]) -> Result<Self, ParamError> {
        PeriodicBox::new(l)
    }
}

impl From<PeriodicBox> for [f64; 3] {
    fn from(b: PeriodicBox) -> [f64; 3] {
        b.lengths.into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_stays_in_box() {
        let b = PeriodicBox::new([2.0, 3.0, 5.0]).unwrap();
        for x in [-1e-18, -2.0, 2.0, 7.5, -100.25, 1e-300, 1.9999999999999998] {
            let w = b.wrap(Vec3::new(x, x, x));
            for k in 0..3 {
                assert!(w[k] >= 0.0 && w[k] < b.lengths()[k], "{x} -> {}", w[k]);
            }
        }
        assert!(b.wrap(Vec3::new(f64::NAN, 0.0, 0.0)).x.is_nan());
    }

    #[test]
    fn min_image_is_shortest() {
        let b = PeriodicBox::cubic(4.0).unwrap();
        let d = b.min_image(Vec3::new(3.5, -3.5, 1.0));
        assert_eq!(d, Vec3::new(-0.5, 0.5, 1.0));
        // Far images take the general path.
        assert_eq!(
            b.min_image(Vec3::new(9.0, -13.0, 0.0)),
            Vec3::new(1.0, -1.0, 0.0)
        );
    }

    #[test]
    fn rejects_bad_lengths() {
        let e = PeriodicBox::new([1.0, -2.0, 1.0]).unwrap_err();
        assert_eq!(e.field, "box.y");
        assert!(PeriodicBox::new([1.0, 1.0, f64::NAN]).is_err());
    }
}
