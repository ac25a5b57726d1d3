//! Periodic orthorhombic simulation box with minimum-image convention, and Lees-Edwards
//! sliding boundaries on top of it.

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

    /// [`PeriodicBox::min_image`] of a `d` less than one and a half lengths out on every axis,
    /// such as the difference of two positions in the box: one conditional shift per axis and
    /// no general path, bitwise `min_image(d)` there (NaN stays NaN; an infinite component
    /// stays infinite where `min_image` gives NaN). A loop over bonds calls it: the general
    /// path's rounding call made the loop keep its values on the stack.
    #[inline(always)]
    pub(crate) fn near_image(&self, d: Vec3) -> Vec3 {
        let l = self.lengths;
        Vec3::new(shift1(d.x, l.x), shift1(d.y, l.y), shift1(d.z, l.z))
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
    let e = shift1(d, l);
    if e.abs() <= 0.5 * l {
        e
    } else {
        d - l * (d * inv).round()
    }
}

/// `d` shifted by one length `l` towards the origin if it lies more than half a length out.
#[inline(always)]
fn shift1(d: f64, l: f64) -> f64 {
    let half = 0.5 * l;
    if d > half {
        d - l
    } else if d < -half {
        d + l
    } else {
        d
    }
}

/// Lees-Edwards sliding-brick boundary conditions on a [`PeriodicBox`] (algorithms.md
/// section 8): flow along x, velocity gradient along y, shear rate `kappa = rate`.
///
/// The periodic image of the box at `y + L_y` is displaced by `offset` along x and moves with
/// x-velocity `rate * L_y` relative to the box (the image at `y - L_y` by `-offset`, with
/// `-rate * L_y`). The offset is `rate * L_y * t` modulo `L_x`, advanced by every drift, so
/// that it follows the positions through the sub-flows of a step. Consequences, all in this
/// type:
/// - minimum image: a separation crossing the y boundary `n` times (`n` in -1, 0, 1 for
///   wrapped positions) loses `n * offset` along x, and the pair's relative velocity loses
///   `n * rate * L_y` along x ([`LeesEdwards::min_image`]);
/// - wrapping: a particle leaving through `y = L_y` re-enters at `y - L_y`, `x - offset`, with
///   x-momentum reduced by `m rate L_y` (and the reverse through `y = 0`).
///
/// The streaming velocity consistent with these images is `u_x(y) = rate (y - L_y / 2)`.
/// With `rate = 0` every operation gives bitwise the periodic result.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LeesEdwards {
    rate: f64,
    /// In `[0, L_x)`.
    offset: f64,
    /// Total variation of the offset so far, the sum of `|rate L_y h|` over drifts: a bound on
    /// how far the images slid between two times (the neighbour list's rebuild test).
    travel: f64,
}

impl LeesEdwards {
    /// Shear rate `rate` (finite; 0 is allowed and reproduces the periodic box), offset 0.
    pub fn new(rate: f64) -> Result<Self, ParamError> {
        if !rate.is_finite() {
            return Err(ParamError::new(
                "shear_rate",
                rate,
                "must be finite (flow along x, gradient along y)",
            ));
        }
        Ok(LeesEdwards {
            rate,
            offset: 0.0,
            travel: 0.0,
        })
    }

    /// Restore a saved state; `offset` must lie in `[0, L_x)`, `travel` be finite and >= 0.
    pub(crate) fn restore(
        rate: f64,
        offset: f64,
        travel: f64,
        bx: &PeriodicBox,
    ) -> Result<Self, ParamError> {
        let le = LeesEdwards::new(rate)?;
        if !(0.0..bx.lengths.x).contains(&offset) {
            return Err(ParamError::new(
                "shear_offset",
                offset,
                format!("must be in [0, L_x = {})", bx.lengths.x),
            ));
        }
        if !(travel.is_finite() && travel >= 0.0) {
            return Err(ParamError::new(
                "shear_travel",
                travel,
                "must be finite and >= 0",
            ));
        }
        Ok(LeesEdwards {
            offset,
            travel,
            ..le
        })
    }

    /// Shear rate `kappa` (inverse time units).
    pub fn rate(&self) -> f64 {
        self.rate
    }

    /// Current x-offset of the image at `y + L_y`, in `[0, L_x)`.
    pub fn offset(&self) -> f64 {
        self.offset
    }

    /// Total distance the images have slid so far (sum of `|rate L_y h|` over drifts).
    pub fn travel(&self) -> f64 {
        self.travel
    }

    /// x-velocity of the image at `y + L_y` relative to the box, `rate * L_y`.
    pub fn image_velocity(&self, bx: &PeriodicBox) -> f64 {
        self.rate * bx.lengths.y
    }

    /// Streaming velocity `u_x(y) = rate (y - L_y / 2)` of the imposed linear profile.
    pub fn streaming_velocity(&self, bx: &PeriodicBox, y: f64) -> f64 {
        self.rate * (y - 0.5 * bx.lengths.y)
    }

    /// Advance the offset by a drift of length `h` (any sign).
    pub(crate) fn advance(&mut self, bx: &PeriodicBox, h: f64) {
        let slide = self.rate * bx.lengths.y * h;
        self.offset = wrap1(self.offset + slide, bx.lengths.x);
        self.travel += slide.abs();
    }

    /// The image of `d = q_i - q_j` closest to the origin, and the x-velocity to add to
    /// `v_i - v_j` for that image (`-n rate L_y` when the image of j lies `n` boxes up).
    /// Bitwise [`PeriodicBox::min_image`] when the offset and rate are 0.
    #[inline(always)]
    pub fn min_image(&self, bx: &PeriodicBox, d: Vec3) -> (Vec3, f64) {
        let (l, inv) = (bx.lengths, bx.inv);
        let n = image_count(d.y, l.y, inv.y);
        let image = Vec3::new(
            image1(d.x - n * self.offset, l.x, inv.x),
            d.y - n * l.y,
            image1(d.z, l.z, inv.z),
        );
        (image, -n * self.rate * l.y)
    }

    /// `q` mapped into the box, and the number of times `n` it crossed the y boundary upwards
    /// (negative: downwards); the caller subtracts `n m rate L_y` from the x-momentum.
    #[inline(always)]
    pub fn wrap(&self, bx: &PeriodicBox, q: Vec3) -> (Vec3, f64) {
        let l = bx.lengths;
        let y = wrap1(q.y, l.y);
        let n = if y == q.y {
            0.0
        } else {
            ((q.y - y) * bx.inv.y).round()
        };
        let x = wrap1(q.x - n * self.offset, l.x);
        (Vec3::new(x, y, wrap1(q.z, l.z)), n)
    }
}

/// The `n` with `d - n l` the image of [`image1`]: same branches, same result.
#[inline(always)]
fn image_count(d: f64, l: f64, inv: f64) -> f64 {
    let half = 0.5 * l;
    let n = if d > half {
        1.0
    } else if d < -half {
        -1.0
    } else {
        0.0
    };
    if (d - n * l).abs() <= half {
        n
    } else {
        (d * inv).round()
    }
}

/// `x` in `[0, l)`: one shift by `l` ([`shift_once`]), or [`far_wrap1`] when that is not
/// enough; a NaN stays NaN.
#[inline(always)]
fn wrap1(x: f64, l: f64) -> f64 {
    if !(x >= l || x < 0.0) {
        return x;
    }
    let y = shift_once(x, l);
    if (0.0..l).contains(&y) {
        y
    } else {
        far_wrap1(x, l)
    }
}

/// `x` shifted by one length `l` towards `[0, l)` if it lies outside (`x - l` at or above `l`,
/// `x + l` below 0), else `x`: the first step of a wrap, written with selects so that loops over
/// many coordinates vectorise (the drift's blocks).
#[inline(always)]
pub(crate) fn shift_once(x: f64, l: f64) -> f64 {
    let y = if x >= l { x - l } else { x };
    if x < 0.0 {
        x + l
    } else {
        y
    }
}

/// [`wrap1`] for `x` more than one length out (or when rounding lands on `l`), and for
/// infinite `x`, which stays as it is.
#[cold]
#[inline(never)]
fn far_wrap1(x: f64, l: f64) -> f64 {
    if x.is_infinite() {
        return x;
    }
    let z = x.rem_euclid(l);
    if z < l {
        z
    } else {
        0.0
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
        assert_eq!(b.wrap(Vec3::new(0.0, f64::INFINITY, 0.0)).y, f64::INFINITY);
        assert_eq!(
            b.wrap(Vec3::new(0.0, 0.0, f64::NEG_INFINITY)).z,
            f64::NEG_INFINITY
        );
    }

    /// The pair fill and the bonds image the difference of two positions in the box with
    /// `near_image`: it must be `min_image` to the bit there, at the half-length ties too.
    #[test]
    fn near_image_is_min_image_for_two_positions_in_the_box() {
        use rand::{Rng, SeedableRng};
        let b = PeriodicBox::new([7.0, 3.3, 10.1]).unwrap();
        let l = b.lengths();
        let same = |d: Vec3| {
            let (near, min) = (b.near_image(d), b.min_image(d));
            (0..3).all(|k| near[k].to_bits() == min[k].to_bits())
        };
        let mut rng = rand::rngs::StdRng::seed_from_u64(7);
        for _ in 0..100_000 {
            let (q1, q2) = (
                b.wrap(Vec3::from_fn(|k, _| rng.random_range(0.0..l[k]))),
                b.wrap(Vec3::from_fn(|k, _| rng.random_range(0.0..l[k]))),
            );
            assert!(same(q1 - q2), "{q1} - {q2}");
        }
        for t in [
            0.0,
            0.5,
            -0.5,
            1.0 - 1e-16,
            -(1.0 - 1e-16),
            0.5 + 1e-16,
            -0.5 - 1e-16,
        ] {
            let d = l * t;
            assert!(same(d), "{d}");
        }
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
    fn lees_edwards_images_slide_along_x() {
        let b = PeriodicBox::new([10.0, 4.0, 5.0]).unwrap();
        let mut le = LeesEdwards::new(0.5).unwrap();
        le.advance(&b, 2.5); // offset = 0.5 * 4 * 2.5 = 5
        assert_eq!(le.offset(), 5.0);
        // i near the top, j near the bottom: j's image lies one box up, shifted by +5 in x and
        // moving at +2 in x, so v_ij loses 2.
        let (d, dv) = le.min_image(&b, Vec3::new(4.5, 3.5, 0.0));
        assert_eq!(d, Vec3::new(-0.5, -0.5, 0.0));
        assert_eq!(dv, -2.0);
        let (d, dv) = le.min_image(&b, Vec3::new(-4.5, -3.5, 0.0));
        assert_eq!(d, Vec3::new(0.5, 0.5, 0.0));
        assert_eq!(dv, 2.0);
        // Leaving through the top re-enters at the bottom, 5 back in x.
        let (q, n) = le.wrap(&b, Vec3::new(1.0, 4.25, 1.0));
        assert_eq!((q, n), (Vec3::new(6.0, 0.25, 1.0), 1.0));
        let (q, n) = le.wrap(&b, Vec3::new(7.0, -0.25, 1.0));
        assert_eq!((q, n), (Vec3::new(2.0, 3.75, 1.0), -1.0));
        le.advance(&b, -3.0);
        assert_eq!((le.offset(), le.travel()), (9.0, 11.0));
        assert_eq!(LeesEdwards::new(f64::NAN).unwrap_err().field, "shear_rate");
    }

    #[test]
    fn zero_shear_is_the_periodic_box() {
        let b = PeriodicBox::new([3.0, 4.0, 5.0]).unwrap();
        let mut le = LeesEdwards::new(0.0).unwrap();
        le.advance(&b, 1.0);
        for d in [
            Vec3::new(2.9, -3.1, 0.3),
            Vec3::new(-1.2, 2.5, -4.9),
            Vec3::new(0.1, 0.2, 0.3),
        ] {
            assert_eq!(le.min_image(&b, d), (b.min_image(d), 0.0));
            assert_eq!(
                le.wrap(&b, d + Vec3::new(0.0, 3.0, 0.0)).0,
                b.wrap(d + Vec3::new(0.0, 3.0, 0.0))
            );
        }
    }

    #[test]
    fn rejects_bad_lengths() {
        let e = PeriodicBox::new([1.0, -2.0, 1.0]).unwrap_err();
        assert_eq!(e.field, "box.y");
        assert!(PeriodicBox::new([1.0, 1.0, f64::NAN]).is_err());
    }
}
