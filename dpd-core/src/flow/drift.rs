use crate::system::System;

/// A: `q_i += h p_i / m_i`, positions wrapped into the box. Exact for any `h`.
///
/// Adds the largest single-particle displacement to the step's drift bound used by blow-up
/// detection, and drops every position-dependent cache.
pub fn drift(sys: &mut System, h: f64) {
    let bx = sys.bx;
    let mut max2: f64 = 0.0;
    for ((q, p), &im) in sys.q.iter_mut().zip(&sys.p).zip(&sys.inv_mass) {
        let d = (h * im) * p;
        let d2 = d.norm_squared();
        // NaN is kept too, so that it poisons the bound.
        if d2 > max2 || d2.is_nan() {
            max2 = d2;
        }
        *q = bx.wrap(*q + d);
    }
    sys.drift_bound += max2.sqrt();
    sys.positions_changed();
}
