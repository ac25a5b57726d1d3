//! Scenes and helpers shared by the catalogue's tests.

use dpd_core::init::{cubic_box, maxwell_momenta, uniform_positions};
use dpd_core::observe::{thermo, ThermoAverages, ThermoSummary};
use dpd_core::params::ParamsBuilder;
use dpd_core::{AdvanceError, Params, Scheme, System};
use dpd_schemes::stability::with_thermostat_friction;

/// `n` particles of mass `mass` at `density`, uniform positions, Maxwell momenta.
pub fn system(
    n: usize,
    density: f64,
    mass: f64,
    params: ParamsBuilder,
    dt: f64,
    seed: u64,
) -> System {
    let params: Params = params.build().unwrap();
    let bx = cubic_box(n, density).unwrap();
    let masses = vec![mass; n];
    System::builder(params.clone(), bx, uniform_positions(&bx, n, seed))
        .momenta(maxwell_momenta(&masses, params.kbt(), seed))
        .masses(masses)
        .dt(dt)
        .seed(seed)
        .build()
        .unwrap()
}

/// The collision frequency of the Lowe-Andersen schemes in these tests: the mean rate at
/// which O relaxes a pair's relative normal velocity at gamma = 4.5, 2 gamma <w_D> with
/// <w_D> = 0.0604 over the fluid's g(r) (docs/design-search.md).
pub const COLLISION_RATE: f64 = 0.54;

/// The thermostat mass of the adaptive (PAdL, PNHL) schemes in these tests: 10 gamma^2 at
/// gamma = 4.5, so that xi = 1 +- 0.07 (docs/design-search.md).
pub const THERMOSTAT_MASS: f64 = 202.5;

/// The standard equilibrium box (algorithms.md section 8): N = 500, density 3, a = 25,
/// gamma = 4.5, k_B T = 1, m = 1, s = 2; collision rate [`COLLISION_RATE`] for schemes
/// with L, thermostat mass [`THERMOSTAT_MASS`] for PAdL and PNHL, and the stability matrix's
/// thermostat friction for `scheme` if it is PNHL's.
pub fn standard_box(scheme: &dyn Scheme, dt: f64, seed: u64) -> System {
    let params =
        (Params::builder().collision_rate(COLLISION_RATE)).thermostat_mass(THERMOSTAT_MASS);
    system(
        500,
        3.0,
        1.0,
        with_thermostat_friction(params, scheme),
        dt,
        seed,
    )
}

/// The low-mass scene (algorithms.md section 8) in a periodic box: N = 500, density 4,
/// m = 0.01, a = 18.5, sigma = 3 (gamma = 4.5 at k_B T = 1), s = 1/2.
pub fn low_mass_box(dt: f64, seed: u64) -> System {
    system(
        500,
        4.0,
        0.01,
        Params::builder().a(18.5).weight_exponent(0.5),
        dt,
        seed,
    )
}

/// Runs `steps` steps, sampling every `every` steps over the last `fraction` of the run.
pub fn averages(
    sys: &mut System,
    scheme: &dyn Scheme,
    steps: u64,
    every: u64,
    fraction: f64,
) -> Result<ThermoSummary, AdvanceError> {
    let mut avg = ThermoAverages::new(steps, fraction).unwrap();
    for _ in 0..steps / every {
        sys.advance(scheme, every)?;
        if avg.wants(sys.step()) {
            avg.record(&thermo(sys));
        }
    }
    Ok(avg.summary())
}

/// Equal positions and momenta (`==` on `f64`: bitwise for the finite values a run keeps).
pub fn same_state(a: &System, b: &System) -> bool {
    a.positions() == b.positions() && a.momenta() == b.momenta()
}
