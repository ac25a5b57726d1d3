use crate::error::ParamError;
use crate::system::System;
use crate::Vec3;
use serde::Serialize;

/// Instantaneous thermodynamic quantities of one state.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Thermo {
    /// `k_B T_K = sum p.p/m / (3 (N - 1))`.
    pub kinetic_temperature: f64,
    /// Numerator of the configurational temperature, `sum_i |F^C_i|^2` (pair and bonded
    /// forces).
    pub config_numerator: f64,
    /// Denominator of the configurational temperature, `sum_i lap_i U` (pairs, bonds, angles).
    pub config_denominator: f64,
    /// Potential energy per particle, `U / N`, pairs and bonds.
    pub potential_energy: f64,
    /// Virial pressure `N k_B T_K / V + (sum_pairs q_ij . F^C_ij + sum_bonds q_ij . F_ij) / (3
    /// V)` (angles, scale-free, add nothing).
    pub pressure: f64,
}

impl Thermo {
    /// `k_B T_C` of this one state (noisy; average numerator and denominator separately).
    pub fn configurational_temperature(&self) -> f64 {
        self.config_numerator / self.config_denominator
    }
}

/// `k_B T_K = sum_i p_i . p_i / m_i / (3 (N - 1))`: the total momentum is conserved, so N - 1
/// particles' worth of degrees of freedom are free. Under shear, of the velocities relative to
/// the streaming profile ([`System::peculiar_velocities`]); with walls, N counts the mobile
/// particles only (frozen ones have zero velocity as far as this sum goes).
pub fn kinetic_temperature(sys: &System) -> f64 {
    let twice_ke: f64 = match sys.shear() {
        None => 2.0 * sys.kinetic_energy(),
        Some(_) => sys
            .peculiar_velocities()
            .iter()
            .zip(sys.masses())
            .map(|(v, m)| m * v.norm_squared())
            .sum(),
    };
    let mobile = match sys.frozen() {
        None => sys.len(),
        Some(frozen) => frozen.iter().filter(|&&f| !f).count(),
    };
    twice_ke / (3.0 * (mobile as f64 - 1.0))
}

/// Measure [`Thermo`] at the current positions and momenta.
///
/// The pair potential, its Laplacian and virial are those of [`crate::potential::Soft`]; the
/// bonded ones those of [`crate::bonded::BondStyle`] and [`crate::bonded::AngleStyle`].
pub fn thermo(sys: &mut System) -> Thermo {
    let n = sys.len() as f64;
    let volume = sys.boundary().volume();
    let tk = kinetic_temperature(sys);
    let bonded = sys.bonded_sums();
    let (u, lap, virial, numerator) = sys.with_forces(|sys, pairs, forces| {
        let (params, kind) = (sys.params(), sys.kinds());
        let (mut u, mut lap, mut virial) = (0.0, 0.0, 0.0);
        for pair in pairs.iter() {
            let soft = params.soft(kind[pair.i as usize], kind[pair.j as usize]);
            u += soft.energy(pair.w);
            lap += soft.laplacian(pair.w);
            virial += soft.virial(pair.w);
        }
        let numerator: f64 = match sys.bonded_forces_now() {
            None => forces.iter().map(|f| f.norm_squared()).sum(),
            Some(bonded) => forces
                .iter()
                .zip(&bonded)
                .map(|(f, b)| (f + b).norm_squared())
                .sum(),
        };
        (u, lap, virial, numerator)
    });
    Thermo {
        kinetic_temperature: tk,
        config_numerator: numerator,
        config_denominator: lap + bonded.laplacian,
        potential_energy: (u + bonded.energy) / n,
        pressure: n * tk / volume + (virial + bonded.virial) / (3.0 * volume),
    }
}

/// [`Thermo`] with its positional parts (T_C's sums, the potential energy, the virial) read
/// at the processed positions `x + k F^C(x) / m` (Vilmart's postprocessing, `k = c dt^2`),
/// on a copy; T_K is the system's own. `F^C(x)` is the evaluation [`thermo`] would make,
/// with the same effect on the system's caches, so a run measuring this keeps the bits of
/// one measuring [`thermo`], at one more force evaluation (at the processed positions).
pub fn processed_thermo(sys: &mut System, k: f64) -> Result<Thermo, ParamError> {
    let kinetic = kinetic_temperature(sys);
    let processed = sys.with_forces(|s, _, forces| {
        let q: Vec<Vec3> = s
            .positions()
            .iter()
            .zip(forces)
            .zip(s.masses())
            .map(|((x, f), m)| x + f * (k / m))
            .collect();
        let mut copy = s.clone();
        copy.set_positions(&q)?;
        Ok::<_, ParamError>(thermo(&mut copy))
    })?;
    Ok(Thermo {
        kinetic_temperature: kinetic,
        ..processed
    })
}
