"""Time per step of OpenMM's DPDIntegrator (CPU platform) on the dpd equilibrium box.

Reduced units mapped to OpenMM's: length 1 nm, mass 1 amu, energy k_B T = 1 kJ/mol (so
T = 120.27 K), time 1 ps. N particles at density 3, conservative force
a (1 - r/r_c) with a = 25 as a CustomNonbondedForce, friction 4.5, r_c = 1, dt = 0.04.
Prints one JSON object.

Usage: python openmm_dpd.py N STEPS THREADS
"""
import json
import sys
import time

import numpy as np
import openmm
from openmm import unit


def main():
    n, steps, threads = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
    side = (n / 3.0) ** (1.0 / 3.0)
    system = openmm.System()
    system.setDefaultPeriodicBoxVectors(
        openmm.Vec3(side, 0, 0), openmm.Vec3(0, side, 0), openmm.Vec3(0, 0, side))
    for _ in range(n):
        system.addParticle(1.0)
    force = openmm.CustomNonbondedForce("0.5*a*rc*(1-r/rc)^2; a=25; rc=1")
    force.setNonbondedMethod(openmm.CustomNonbondedForce.CutoffPeriodic)
    force.setCutoffDistance(1.0)
    for _ in range(n):
        force.addParticle([])
    system.addForce(force)
    kelvin = 1.0 / (unit.MOLAR_GAS_CONSTANT_R.value_in_unit(unit.kilojoule_per_mole / unit.kelvin))
    integrator = openmm.DPDIntegrator(kelvin, 4.5, 1.0, 0.04)
    platform = openmm.Platform.getPlatformByName("CPU")
    context = openmm.Context(system, integrator, platform, {"Threads": str(threads)})
    rng = np.random.default_rng(1)
    context.setPositions(rng.uniform(0, side, size=(n, 3)))
    context.setVelocitiesToTemperature(kelvin, 1)
    integrator.step(20)
    start = time.perf_counter()
    integrator.step(steps)
    context.getState(getEnergy=True)
    seconds = time.perf_counter() - start
    print(json.dumps({
        "engine": "openmm", "scheme": "DPDIntegrator", "n": n, "threads": threads,
        "us_per_step": round(seconds / steps * 1e6, 1),
        "ns_per_particle_step": round(seconds / (steps * n) * 1e9, 1),
    }))


if __name__ == "__main__":
    main()
