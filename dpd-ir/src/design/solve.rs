//! Numerical pieces of the design: a damped Gauss-Newton solver for the order conditions and
//! the rank of their Jacobian. Hand-written: at most [`crate::lang::MAX_PARAMETERS`] unknowns,
//! so the normal equations are at most 3 x 3.

/// A residual map: `None` where the scheme cannot be built (e.g. a sweep running backwards).
pub type Residuals<'a> = dyn Fn(&[f64]) -> Option<Vec<f64>> + 'a;

/// Converged when the residual's Euclidean norm is below this: the conditions are sums of
/// products of coefficients of size about one, evaluated with rounding near 1e-15.
pub const CONVERGED: f64 = 1e-11;

/// Most Gauss-Newton iterations from one start.
const MAX_ITERATIONS: usize = 60;

fn norm(r: &[f64]) -> f64 {
    r.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The Jacobian by central differences, column per unknown.
pub fn jacobian(f: &Residuals, x: &[f64]) -> Option<Vec<Vec<f64>>> {
    (0..x.len())
        .map(|j| {
            let h = 1e-6 * (1.0 + x[j].abs());
            let (mut lo, mut hi) = (x.to_vec(), x.to_vec());
            lo[j] -= h;
            hi[j] += h;
            let (a, b) = (f(&lo)?, f(&hi)?);
            Some(a.iter().zip(&b).map(|(a, b)| (b - a) / (2.0 * h)).collect())
        })
        .collect()
}

/// Solves `m x = v` (m symmetric positive definite, small) by Gaussian elimination with
/// partial pivoting; `None` if singular.
fn solve_small(mut m: Vec<Vec<f64>>, mut v: Vec<f64>) -> Option<Vec<f64>> {
    let n = v.len();
    for k in 0..n {
        let p = (k..n).max_by(|&a, &b| m[a][k].abs().total_cmp(&m[b][k].abs()))?;
        if m[p][k] == 0.0 {
            return None;
        }
        m.swap(k, p);
        v.swap(k, p);
        eliminate_below(&mut m, &mut v, k);
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|j| m[k][j] * x[j]).sum();
        x[k] = (v[k] - s) / m[k][k];
    }
    Some(x)
}

/// One step of Gaussian elimination: subtracts multiples of row `k` of `m` (and entry `k` of
/// `v`) from the rows below so that column `k` vanishes there.
fn eliminate_below(m: &mut [Vec<f64>], v: &mut [f64], k: usize) {
    let (top, below) = m.split_at_mut(k + 1);
    let pivot = &top[k];
    for (i, row) in below.iter_mut().enumerate() {
        let f = row[k] / pivot[k];
        for (x, p) in row.iter_mut().zip(pivot).skip(k) {
            *x -= f * p;
        }
        v[k + 1 + i] -= f * v[k];
    }
}

/// Levenberg-Marquardt from `x0`; the point where the residual vanishes, or `None` if it
/// does not converge or leaves `bounds` (widened by 5 % of each range).
pub fn newton(f: &Residuals, x0: &[f64], bounds: &[(f64, f64)]) -> Option<Vec<f64>> {
    let inside = |x: &[f64]| {
        x.iter().zip(bounds).all(|(v, (lo, hi))| {
            let slack = 0.05 * (hi - lo);
            *v >= lo - slack && *v <= hi + slack
        })
    };
    let mut x = x0.to_vec();
    let mut r = f(&x)?;
    let mut lambda = 1e-3;
    for _ in 0..MAX_ITERATIONS {
        if norm(&r) < CONVERGED {
            return inside(&x).then_some(x);
        }
        let before = norm(&r);
        let j = jacobian(f, &x)?;
        let n = x.len();
        let jtj: Vec<Vec<f64>> = (0..n)
            .map(|a| (0..n).map(|b| dot(&j[a], &j[b])).collect())
            .collect();
        let jtr: Vec<f64> = (0..n).map(|a| -dot(&j[a], &r)).collect();
        let mut improved = false;
        for _ in 0..12 {
            let mut m = jtj.clone();
            for (a, row) in m.iter_mut().enumerate() {
                row[a] += lambda * (1.0 + jtj[a][a]);
            }
            let Some(step) = solve_small(m, jtr.clone()) else {
                lambda *= 10.0;
                continue;
            };
            let trial: Vec<f64> = x.iter().zip(&step).map(|(a, b)| a + b).collect();
            if let Some(rt) = f(&trial).filter(|rt| norm(rt) < norm(&r)) {
                x = trial;
                r = rt;
                lambda = (lambda / 10.0).max(1e-15);
                improved = true;
                break;
            }
            lambda *= 10.0;
        }
        // stalled at a local minimum of |r| that is not a root
        if !improved || !inside(&x) || norm(&r) > 0.999 * before {
            return None;
        }
    }
    (norm(&r) < CONVERGED && inside(&x)).then_some(x)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `x` with each coordinate replaced by the nearest fraction `p/q` (`q <= 24`) within `1e-6`
/// when the residual there still vanishes (below [`CONVERGED`]): a solution found numerically
/// next to a rational point (Strang's 1/2, a vanishing coefficient 0) is reported at that point,
/// where the order analysis sees the exact cancellations. Coordinates are tried all together,
/// then one at a time; `x` itself when no snap keeps the residual.
pub fn rationalise(f: &Residuals, x: &[f64]) -> Vec<f64> {
    let near = |v: f64| {
        (1..=24)
            .map(|q| (v * q as f64).round() / q as f64)
            .find(|r| (r - v).abs() <= 1e-6 * (1.0 + v.abs()))
    };
    let vanishes = |y: &[f64]| f(y).is_some_and(|r| norm(&r) < CONVERGED);
    let all: Vec<f64> = x.iter().map(|&v| near(v).unwrap_or(v)).collect();
    if all != x && vanishes(&all) {
        return all;
    }
    let mut y = x.to_vec();
    for k in 0..x.len() {
        if let Some(r) = near(x[k]) {
            let mut trial = y.clone();
            trial[k] = r;
            if vanishes(&trial) {
                y = trial;
            }
        }
    }
    y
}

/// Rank of the Jacobian at `x`: the number of independent conditions there (pivots above
/// 1e-6 of the largest). The solution set has dimension `unknowns - rank` near `x`.
pub fn rank(f: &Residuals, x: &[f64]) -> usize {
    let Some(cols) = jacobian(f, x) else {
        return 0;
    };
    // Gram matrix of the columns: same rank as the Jacobian.
    let n = cols.len();
    let mut m: Vec<Vec<f64>> = (0..n)
        .map(|a| (0..n).map(|b| dot(&cols[a], &cols[b])).collect())
        .collect();
    let scale = (0..n).map(|a| m[a][a]).fold(0.0, f64::max);
    let mut rank = 0;
    for k in 0..n {
        let Some(p) = (k..n).max_by(|&a, &b| m[a][k].abs().total_cmp(&m[b][k].abs())) else {
            break;
        };
        if m[p][k].abs() <= 1e-10 * scale || scale == 0.0 {
            continue;
        }
        m.swap(k, p);
        eliminate_below(&mut m, &mut vec![0.0; n], k);
        rank += 1;
    }
    rank
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn newton_finds_the_real_root_of_a_cubic_system() {
        // x^3 = -2 (1 - x)^3 / 8, i.e. 2 a^3 + x^3 = 0 with a = (1 - x)/2
        let f = |x: &[f64]| {
            let a = (1.0 - x[0]) / 2.0;
            Some(vec![2.0 * a * a * a + x[0] * x[0] * x[0]])
        };
        let x = newton(&f, &[-1.5], &[(-2.0, 2.0)]).unwrap();
        let x0 = -(2f64.cbrt()) / (2.0 - 2f64.cbrt());
        assert!((x[0] - x0).abs() < 1e-10, "{x:?}");
        assert_eq!(rank(&f, &x), 1);
        // no real root of x^2 + 1
        let g = |x: &[f64]| Some(vec![x[0] * x[0] + 1.0]);
        assert!(newton(&g, &[0.5], &[(-2.0, 2.0)]).is_none());
    }
}
