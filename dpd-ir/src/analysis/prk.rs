//! Partitioned Runge-Kutta tables: the published third-order conditions and a general order
//! check through the free-algebra engine.
//!
//! A table `(b, bh)` is the step `F(b_1) A(bh_1) F(b_2) A(bh_2) ...`: kick first. In the
//! engine's convention (first applied leftmost) the conditions (13), (14) and (16) are the
//! coefficients of the words AB, AAB and BBA of `B(b_1) A(bh_1) B(b_2) A(bh_2) B(b_3) A(bh_3)`,
//! which together with the sums (12), (15) are all order-3 conditions (the free Lie algebra
//! on two letters has dimensions 2, 1, 2 in degrees 1, 2, 3).

use super::{analyse, Analysis};
use crate::program::{Coeff, Flow, Stage, SweepOrder};

/// Residuals (left side minus right side) of the published order conditions (12)-(16) of a
/// three-stage PRK table with momentum weights `b` and position weights `bh`.
pub fn prk3_conditions(b: [f64; 3], bh: [f64; 3]) -> [f64; 5] {
    let [b1, b2, b3] = b;
    let [c1, c2, c3] = bh;
    [
        b1 + b2 + b3 - 1.0,
        b2 * c1 + b3 * (c1 + c2) - 0.5,
        b2 * c1 * c1 + b3 * (c1 + c2) * (c1 + c2) - 1.0 / 3.0,
        c1 + c2 + c3 - 1.0,
        c1 * b1 * b1 + c2 * (b1 + b2) * (b1 + b2) + c3 * (b1 + b2 + b3) * (b1 + b2 + b3)
            - 1.0 / 3.0,
    ]
}

/// The stages `F(b_1) A(bh_1) F(b_2) A(bh_2) ...` of a table; if one list is longer, its
/// extra entries follow in turn. The full-force stages share stream 1 (frozen noise).
pub fn prk_stages(b: &[Coeff], bh: &[Coeff]) -> Vec<Stage> {
    let stage = |flow: Flow, coeff: &Coeff, stream: u8| Stage {
        flow,
        coeff: coeff.clone(),
        stream,
        order: SweepOrder::Forward,
        group: None,
    };
    (0..b.len().max(bh.len()))
        .flat_map(|i| {
            let kick = b.get(i).map(|c| stage(Flow::F, c, 1));
            let drift = bh.get(i).map(|c| stage(Flow::A, c, 0));
            kick.into_iter().chain(drift)
        })
        .collect()
}

/// The analysis of a table's step; its `deterministic_order` is the PRK order (F acts as B).
pub fn analyse_prk(b: &[Coeff], bh: &[Coeff]) -> Analysis {
    analyse(&prk_stages(b, bh))
}
