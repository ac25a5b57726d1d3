//! The checks the sections share and the limits they enforce.

use dpd_core::ParamError;

/// Most steps of one run: a longer run is refused rather than left to run for days.
pub const MAX_STEPS: u64 = 1_000_000_000;
/// Most worker threads per core.
pub const MAX_THREADS_PER_CORE: usize = 8;
/// Most particles of a scene.
pub const MAX_PARTICLES: usize = 100_000_000;

/// Cores of this machine (1 if unknown).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// `Ok` when `ok`, else the error naming `key`, its `value` and what is `allowed`.
pub fn require(key: &str, value: impl ToString, ok: bool, allowed: &str) -> Result<(), ParamError> {
    if ok {
        Ok(())
    } else {
        Err(ParamError::new(key, value, allowed))
    }
}

pub fn positive(key: &str, v: f64) -> Result<(), ParamError> {
    require(key, v, v.is_finite() && v > 0.0, "must be finite and > 0")
}

pub fn non_negative(key: &str, v: f64) -> Result<(), ParamError> {
    require(key, v, v.is_finite() && v >= 0.0, "must be finite and >= 0")
}

/// Checks that a run of `time` at step `key` = `dt` (already checked positive) has between 1
/// and [`MAX_STEPS`] steps.
pub fn steps_in_range(time: f64, key: &str, dt: f64) -> Result<(), ParamError> {
    let steps = (time / dt).round();
    require(
        key,
        dt,
        steps >= 1.0,
        &format!(
            "gives round(time / {key}) = 0 steps with time = {time}: must be at most twice \
             time, {}",
            2.0 * time
        ),
    )?;
    require(
        key,
        dt,
        steps <= MAX_STEPS as f64,
        &format!(
            "gives {steps:e} steps with time = {time}, more than the {MAX_STEPS:e} steps a run \
             may take: raise {key} or shorten time"
        ),
    )
}
