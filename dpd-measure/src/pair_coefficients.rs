//! The pair-force coefficients of every pair of particle types, as a scene's `[pairs]` or a
//! data file's `pair_style dpd` coefficients give them.

use dpd_core::params::ParamsBuilder;

/// Matrices indexed by type id, symmetric: the repulsion `a_ij`, the friction `gamma_ij`
/// (sigma_ij^2 = 2 gamma_ij k_B T) and the cut-off `r_c,ij` (in units of the largest, 1).
#[derive(Clone, Debug, PartialEq)]
pub struct PairCoefficients {
    pub a: Vec<Vec<f64>>,
    pub gamma: Vec<Vec<f64>>,
    pub rc: Vec<Vec<f64>>,
}

impl PairCoefficients {
    /// `builder` with these coefficients (a matrix of one value runs as that one value).
    pub fn apply(self, builder: ParamsBuilder) -> ParamsBuilder {
        builder
            .a_matrix(self.a)
            .gamma_matrix(self.gamma)
            .rc_matrix(self.rc)
    }

    /// Pair `(i, j)`'s coefficients `[a, gamma, r_c]`.
    pub fn of(&self, i: usize, j: usize) -> [f64; 3] {
        [self.a[i][j], self.gamma[i][j], self.rc[i][j]]
    }

    /// The first pair `(i, j)`, `i <= j`, whose coefficients differ from `other`'s.
    pub fn first_difference(&self, other: &Self) -> Option<(usize, usize)> {
        (0..self.a.len())
            .flat_map(|i| (i..self.a.len()).map(move |j| (i, j)))
            .find(|&(i, j)| self.of(i, j) != other.of(i, j))
    }
}
