//! The critical step size: the smallest dt at which an error reaches a threshold
//! (algorithms.md section 7), by log-log interpolation between the last point below and the
//! first point at or above it, never by extrapolation; where the error changes sign between
//! those two points the reading is flagged with the bracket that holds it.

use serde::Serialize;
use std::fmt;

/// Where an error curve first reaches a threshold.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum Critical {
    /// Interpolated (or hit exactly) at `dt`.
    At { dt: f64 },
    /// Read at `dt` as for `At`, but the error changes sign between the last point below the
    /// threshold (`below`) and the first at or above it (`above`): a power law of dt does not
    /// pass through zero, so the data only place the critical dt in `(below, above]`.
    SignChange { dt: f64, below: f64, above: f64 },
    /// The smallest dt already errs too much: the critical dt is below `dt_min`.
    BelowRange { dt_min: f64 },
    /// No point reaches the threshold: the critical dt is above `dt_max`.
    NotReached { dt_max: f64 },
    /// The first point at or above the threshold blew up, so there is nothing to interpolate:
    /// the critical dt lies in `(below, above]`.
    BlowUp { below: f64, above: f64 },
}

impl Critical {
    /// The critical dt where it was found inside the grid.
    pub fn dt(self) -> Option<f64> {
        match self {
            Critical::At { dt } | Critical::SignChange { dt, .. } => Some(dt),
            _ => None,
        }
    }

    /// A short form for wide tables: `0.0412`, `0.0412*` (sign change), `< 0.0100`, `>
    /// 0.2000`, `(0.0596, 0.0745]` (blow-up).
    pub fn compact(self) -> String {
        match self {
            Critical::SignChange { dt, .. } => format!("{dt:.4}*"),
            Critical::BlowUp { below, above } => format!("({below:.4}, {above:.4}]"),
            other => other.to_string(),
        }
    }
}

impl fmt::Display for Critical {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Critical::At { dt } => write!(f, "{dt:.4}"),
            Critical::SignChange { dt, below, above } => {
                write!(f, "{dt:.4} (sign change in ({below:.4}, {above:.4}])")
            }
            Critical::BelowRange { dt_min } => write!(f, "< {dt_min:.4}"),
            Critical::NotReached { dt_max } => write!(f, "> {dt_max:.4}"),
            Critical::BlowUp { below, above } => write!(f, "({below:.4}, {above:.4}] blow-up"),
        }
    }
}

/// The critical dt of the curve `points` = `(dt, signed relative error)`, sorted by increasing
/// dt, where |error| first reaches `threshold`; an infinite or NaN error marks a point that blew
/// up. Between the two points around the crossing log |error| is taken as linear in log dt (a
/// power law); where their errors have opposite signs the result is [`Critical::SignChange`].
/// `None` for an empty curve.
pub fn critical_dt(points: &[(f64, f64)], threshold: f64) -> Option<Critical> {
    let (&(dt_min, _), &(dt_max, _)) = (points.first()?, points.last()?);
    let Some(k) = points
        .iter()
        .position(|&(_, e)| e.is_nan() || e.abs() >= threshold)
    else {
        return Some(Critical::NotReached { dt_max });
    };
    let (dt_b, e_b) = points[k];
    if e_b.abs() == threshold {
        return Some(Critical::At { dt: dt_b });
    }
    if k == 0 {
        return Some(Critical::BelowRange { dt_min });
    }
    let (dt_a, e_a) = points[k - 1];
    if !e_b.is_finite() {
        return Some(Critical::BlowUp {
            below: dt_a,
            above: dt_b,
        });
    }
    if e_a == 0.0 {
        // The log-log line from an error of exactly zero rises vertically at dt_b.
        return Some(Critical::At { dt: dt_b });
    }
    let (a, b) = (e_a.abs().ln(), e_b.abs().ln());
    let t = (threshold.ln() - a) / (b - a);
    let dt = (dt_a.ln() + t * (dt_b.ln() - dt_a.ln())).exp();
    Some(if e_a * e_b < 0.0 {
        Critical::SignChange {
            dt,
            below: dt_a,
            above: dt_b,
        }
    } else {
        Critical::At { dt }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn power_laws_are_interpolated_exactly() {
        // e = 10 dt^2 crosses 0.1 at dt = 0.1; grid points bracket it.
        let curve: Vec<_> = [0.05, 0.08, 0.12, 0.2]
            .iter()
            .map(|&dt| (dt, 10.0 * dt * dt))
            .collect();
        let c = critical_dt(&curve, 0.1).unwrap();
        assert_relative_eq!(c.dt().unwrap(), 0.1, max_relative = 1e-12);
    }

    #[test]
    fn the_first_crossing_counts() {
        // A curve that goes 5 %, 12 %, -3 %, 20 %.
        let curve = [(0.05, 0.05), (0.1, 0.12), (0.15, -0.03), (0.2, 0.2)];
        let dt = critical_dt(&curve, 0.1).unwrap().dt().unwrap();
        assert!(dt > 0.05 && dt < 0.1, "{dt}");
        // Negative errors cross too.
        let cold = [(0.05, -0.05), (0.1, -0.2)];
        let dt = critical_dt(&cold, 0.1).unwrap().dt().unwrap();
        assert_relative_eq!(dt, 0.05 * 2f64.powf(0.5), max_relative = 1e-12);
    }

    /// An error through zero is no power of dt: the reading is kept, with the bracket. Here
    /// -2 % at 0.1 and +8 % at 0.2 (a sign change) around 5 %, +8 % and +32 % at 0.2 and 0.4
    /// (none) around 10 %.
    #[test]
    fn a_sign_change_is_flagged_with_its_bracket() {
        let curve = [(0.05, -0.01), (0.1, -0.02), (0.2, 0.08), (0.4, 0.32)];
        let Some(Critical::SignChange { dt, below, above }) = critical_dt(&curve, 0.05) else {
            panic!("{:?}", critical_dt(&curve, 0.05));
        };
        assert_eq!((below, above), (0.1, 0.2));
        assert_relative_eq!(
            dt,
            0.1 * 2f64.powf(2.5f64.ln() / 4f64.ln()),
            max_relative = 1e-12
        );
        let c = critical_dt(&curve, 0.04).unwrap();
        assert_eq!(c.to_string(), "0.1414 (sign change in (0.1000, 0.2000])");
        assert_eq!(c.compact(), "0.1414*");
        let c = critical_dt(&curve, 0.1).unwrap();
        assert!(matches!(c, Critical::At { .. }), "{c:?}");
    }

    #[test]
    fn a_threshold_hit_exactly_is_that_point() {
        let curve = [(0.05, 0.05), (0.1, 0.1), (0.2, 0.3)];
        assert_eq!(critical_dt(&curve, 0.1), Some(Critical::At { dt: 0.1 }));
        let first = [(0.05, 0.1), (0.1, 0.3)];
        assert_eq!(critical_dt(&first, 0.1), Some(Critical::At { dt: 0.05 }));
    }

    #[test]
    fn never_extrapolated() {
        let low = [(0.05, 0.01), (0.1, 0.05)];
        assert_eq!(
            critical_dt(&low, 0.1),
            Some(Critical::NotReached { dt_max: 0.1 })
        );
        let high = [(0.05, 0.2), (0.1, 0.5)];
        assert_eq!(
            critical_dt(&high, 0.1),
            Some(Critical::BelowRange { dt_min: 0.05 })
        );
        assert_eq!(critical_dt(&[], 0.1), None);
    }

    #[test]
    fn unstable_points_bracket_without_interpolation() {
        let curve = [(0.05, 0.01), (0.1, 0.05), (0.2, f64::INFINITY)];
        let c = critical_dt(&curve, 0.1);
        assert_eq!(
            c,
            Some(Critical::BlowUp {
                below: 0.1,
                above: 0.2
            })
        );
        assert_eq!(c.unwrap().compact(), "(0.1000, 0.2000]");
        let nan = [(0.05, 0.01), (0.1, f64::NAN)];
        assert!(matches!(
            critical_dt(&nan, 0.1),
            Some(Critical::BlowUp { .. })
        ));
    }

    #[test]
    fn a_zero_error_below_rises_at_the_next_point() {
        let curve = [(0.05, 0.0), (0.1, 0.5)];
        assert_eq!(critical_dt(&curve, 0.1), Some(Critical::At { dt: 0.1 }));
    }
}
