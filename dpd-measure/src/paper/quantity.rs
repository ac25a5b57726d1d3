//! The quantities a paper item can compare: their names, as published rows use them.

/// The quantities a published row can name. Per scheme (rows without `dt`, sweeps only):
/// critical step sizes at 10 % and 1 % relative error of the sweep's observable, the
/// efficiencies (critical dt per ms of a step, relative to the sweep's reference scheme) at
/// both thresholds, and the largest stable grid dt. Per (scheme, dt): means over the runs'
/// averages; `*_temperature_error` is |T - k_B T| / k_B T; `channel_temperature` is the
/// particle-weighted mean of the slab temperatures of `[profile]` (each sample's slab velocity
/// subtracted).
pub const QUANTITIES: [&str; 13] = [
    "critical_dt_10",
    "critical_dt_1",
    "efficiency",
    "efficiency_1",
    "stability_dt",
    "kinetic_temperature",
    "kinetic_temperature_error",
    "configurational_temperature",
    "configurational_temperature_error",
    "potential_energy",
    "diffusion",
    "shear_viscosity",
    "channel_temperature",
];

/// The quantities of [`QUANTITIES`] that are time steps, which a paper may print as steps of
/// its grid (`[published_grid]`).
pub const STEPS: [&str; 3] = ["critical_dt_10", "critical_dt_1", "stability_dt"];

/// Whether `name` is one of [`QUANTITIES`].
pub fn is_quantity(name: &str) -> bool {
    QUANTITIES.contains(&name)
}
