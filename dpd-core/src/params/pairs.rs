//! Coefficients per pair of particle types: the validated symmetric matrices of the builder
//! (`a`, `gamma_matrix`, `rc_matrix`) and the view of them a pair loop keeps in registers
//! ([`Coefficients`]).

use crate::error::ParamError;
use crate::potential::Soft;

/// `rows` as a row-major symmetric `types x types` matrix of finite values that `check`
/// accepts (it returns what a valid value is); the errors name `field[i][j]`.
pub(super) fn symmetric(
    field: &str,
    rows: &[Vec<f64>],
    types: usize,
    check: impl Fn(f64) -> Result<(), String>,
) -> Result<Vec<f64>, ParamError> {
    if rows.len() != types {
        return Err(ParamError::new(
            field,
            format!("{} rows", rows.len()),
            format!("needs one row per particle type ({types}, the rows of a)"),
        ));
    }
    let mut out = Vec::with_capacity(types * types);
    for (i, row) in rows.iter().enumerate() {
        if row.len() != types {
            return Err(ParamError::new(
                format!("{field}[{i}]"),
                format!("{} entries", row.len()),
                format!("must have {types} entries (a square matrix)"),
            ));
        }
        for (j, &v) in row.iter().enumerate() {
            let name = format!("{field}[{i}][{j}]");
            if !v.is_finite() {
                return Err(ParamError::new(name, v, "must be finite"));
            }
            check(v).map_err(|allowed| ParamError::new(&name, v, allowed))?;
            if v != rows[j][i] {
                return Err(ParamError::new(
                    name,
                    v,
                    format!("must equal {field}[{j}][{i}] = {} (symmetric)", rows[j][i]),
                ));
            }
            out.push(v);
        }
    }
    Ok(out)
}

/// The coefficients of every pair of types, as a value a pair loop keeps in registers
/// ([`crate::Params::coefficients`]): the repulsion `a_ij` (energy per length), and the
/// friction `gamma_ij`, noise amplitude `sigma_ij = sqrt(2 gamma_ij k_B T)` and cut-off
/// `r_c,ij` (length), each stored per pair of types only when the pairs' values differ. With
/// one type, or one value for every pair, a lookup reads no types.
#[derive(Clone, Copy, Debug)]
pub struct Coefficients<'a> {
    pub(super) a: &'a [f64],
    pub(super) types: usize,
    /// The largest cut-off (every pair's, when `cutoff` is empty).
    pub(super) rc: f64,
    /// Friction and noise amplitude of every pair when `gamma` is empty.
    pub(super) uniform: (f64, f64),
    /// `gamma_ij` and `sigma_ij`, row-major, or empty.
    pub(super) gamma: &'a [f64],
    pub(super) sigma: &'a [f64],
    /// `r_c,ij`, row-major, or empty.
    pub(super) cutoff: &'a [f64],
}

impl Coefficients<'_> {
    /// Repulsion between types `ti` and `tj`.
    #[inline(always)]
    pub fn a(self, ti: u16, tj: u16) -> f64 {
        self.a[self.index(ti, tj)]
    }

    /// Whether the pairs' frictions differ (then [`Coefficients::friction`] reads types).
    #[inline(always)]
    pub fn friction_by_type(self) -> bool {
        !self.gamma.is_empty()
    }

    /// Whether the pairs' cut-offs differ (then [`Coefficients::rc`] reads types).
    #[inline(always)]
    pub fn cutoff_by_type(self) -> bool {
        !self.cutoff.is_empty()
    }

    /// `(gamma_ij, sigma_ij)` of two particles, `types` giving their types (called only when
    /// the frictions differ).
    #[inline(always)]
    pub fn friction(self, types: impl FnOnce() -> (u16, u16)) -> (f64, f64) {
        if self.gamma.is_empty() {
            self.uniform
        } else {
            let (ti, tj) = types();
            let k = self.index(ti, tj);
            (self.gamma[k], self.sigma[k])
        }
    }

    /// The cut-off `r_c,ij` of two particles, `types` giving their types (called only when
    /// the cut-offs differ).
    #[inline(always)]
    pub fn rc(self, types: impl FnOnce() -> (u16, u16)) -> f64 {
        if self.cutoff.is_empty() {
            self.rc
        } else {
            let (ti, tj) = types();
            self.cutoff[self.index(ti, tj)]
        }
    }

    /// The soft repulsion between two particles, `types` giving their types, with their
    /// cut-off. With one type `types` is not called: a pair loop then loads two values fewer
    /// per pair.
    #[inline(always)]
    pub fn soft(self, types: impl FnOnce() -> (u16, u16)) -> Soft {
        if self.types == 1 {
            return Soft::new(self.a[0], self.rc);
        }
        let (ti, tj) = types();
        let k = self.index(ti, tj);
        let rc = if self.cutoff.is_empty() {
            self.rc
        } else {
            self.cutoff[k]
        };
        Soft::new(self.a[k], rc)
    }

    #[inline(always)]
    fn index(self, ti: u16, tj: u16) -> usize {
        ti as usize * self.types + tj as usize
    }
}
