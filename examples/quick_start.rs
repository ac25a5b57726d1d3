//! The library quick start of README.md: build the standard box, define a scheme with
//! `dpd_scheme!`, step it, and read the temperatures. tests/readme.rs runs it and checks that
//! README.md shows this file verbatim from the first `use`.

use dpd::observe::{thermo, ThermoAverages};
use dpd::{dpd_scheme, init, Params};

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    // The standard box: N = 500 at density 3, a = 25, gamma = 4.5, k_B T = 1.
    let params = Params::builder().a(25.0).gamma(4.5).kbt(1.0).build()?;
    let mut sys = init::equilibrium_box(params, 500, 3.0, 1)?
        .dt(0.05)
        .build()?;

    // ABOBA with the exact pairwise O sweep, compiled into straight-line calls; the macro
    // proves the order claims at compile time.
    let aboba = dpd_scheme!("ABOBA", order >= 2, invariant_order >= 2);

    // 200 steps (10 time units), averaging over the last half every 10 steps. `advance`
    // undoes and reports a step that blows up.
    let steps = 200;
    let mut averages = ThermoAverages::new(steps, 0.5)?;
    for _ in 0..steps / 10 {
        sys.advance(&aboba, 10)?;
        if averages.wants(sys.step()) {
            averages.record(&thermo(&mut sys));
        }
    }
    let s = averages.summary();
    println!(
        "T_K = {:.3}, T_C = {:.3}, P = {:.2}",
        s.kinetic_temperature, s.configurational_temperature, s.pressure
    );
    Ok(())
}
