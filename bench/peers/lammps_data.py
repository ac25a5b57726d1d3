"""LAMMPS on a data file written by `dpd run --write-data`: the input, and a timed run on MPI ranks.

`setup` reads the file's atoms, velocities and the pair dpd coefficients of its one atom
type (a, gamma, r_c) and, for atom style bond, its harmonic bonds, bonded beads keeping their
pair forces (special_bonds lj 1 1 1, the DPD convention). The integrator is LAMMPS's velocity
Verlet (`pair_style dpd` with its noise + `fix nve`) or, given a plugin and a scheme, the
plugin's `fix dpd/split SCHEME` with `pair_style dpd/soft` (the same a, gamma and k_B T):
docs/lammps.md. Neighbour skin SKIN (0: the list rebuilt every step; else when an atom has moved
half the skin); WARMUP steps, then the timed run.

Run as a script, it runs that input with `MPIRUN -np RANKS LMP` and prints one JSON object: the
wall time per step of the timed run (LAMMPS's loop time, setup excluded) and the thermo
temperature and pressure of its last step, so that a blow-up shows (LAMMPS's error, or a
non-finite or absurd temperature); with `--thermo K`, also their means over the timed run
(every K steps) with the standard error of 10 block means.

Usage: python lammps_data.py --lmp LMP --mpirun MPIRUN [--ranks 2] [--warmup 20] [--thermo K]
           [--plugin SO --scheme SCHEME] FILE.data STEPS DT SKIN
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import tempfile

KT = 1.0
SEED = 34387


def header(data):
    """(atom style, (a, gamma, r_c)) from the data file's header, which must have one atom type."""
    lines = []
    with open(data) as f:
        for line in f:
            lines.append(line.strip())
            if line.startswith("Atoms"):
                break
    types = next((int(line.split()[0]) for line in lines if line.endswith("atom types")), 0)
    if types != 1 or "PairIJ Coeffs # dpd" not in lines:
        raise SystemExit(f"{data}: {types} atom types; expected one with 'PairIJ Coeffs # dpd', "
                         "as `dpd run --write-data` writes them")
    _, _, a, gamma, cutoff = lines[lines.index("PairIJ Coeffs # dpd") + 2].split()
    return lines[-1].partition("#")[2].strip() or "atomic", (float(a), float(gamma), float(cutoff))


def setup(data, dt, skin, plugin=None, scheme=None):
    """The LAMMPS input of the module's docstring up to its runs."""
    style, (a, gamma, cutoff) = header(data)
    check = "no" if skin == 0 else "yes"
    bonds = "bond_style harmonic\nspecial_bonds lj 1 1 1\n" if style == "bond" else ""
    if plugin:
        # pair dpd, which read the file's coefficients, is replaced by dpd/soft. `tally
        # evaluation`: the thermo step at the end of a run costs no extra force evaluation.
        integrator = (f"plugin load {plugin}\npair_style dpd/soft {cutoff!r}\n"
                      f"pair_coeff 1 1 {a!r}\nfix 1 all dpd/split \"{scheme}\" {KT!r} {gamma!r} "
                      f"{cutoff!r} {SEED} tally evaluation")
    else:
        integrator = "fix 1 all nve"
    return f"""units lj
atom_style {style}
comm_modify vel yes
pair_style dpd {KT!r} {cutoff!r} {SEED}
{bonds}read_data {data}
neighbor {skin!r} bin
neigh_modify every 1 delay 0 check {check}
{integrator}
timestep {dt!r}
"""


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--lmp", required=True)
    p.add_argument("--mpirun", required=True)
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--warmup", type=int, default=20)
    p.add_argument("--plugin", help="dpdsplitplugin.so: with --scheme, fix dpd/split for fix nve")
    p.add_argument("--scheme", help="an exported scheme, as given to `dpd export lammps`")
    p.add_argument("--thermo", type=int, default=0,
                   help="thermo output every K steps of the timed run, averaged (default: its ends)")
    p.add_argument("data")
    p.add_argument("steps", type=int)
    p.add_argument("dt", type=float)
    p.add_argument("skin", type=float)
    args = p.parse_args()
    if (args.plugin is None) != (args.scheme is None):
        p.error("--plugin and --scheme go together")
    text = setup(os.path.abspath(args.data), args.dt, args.skin, args.plugin, args.scheme)
    text += (f"thermo_style custom step temp press\nrun {args.warmup}\n"
             f"thermo {args.thermo}\nrun {args.steps}\n")
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, "in.lammps")
        with open(path, "w") as f:
            f.write(text)
        command = [args.mpirun, "-np", str(args.ranks), args.lmp, "-in", path, "-log", "none", "-nocite"]
        out = subprocess.run(command, stdin=subprocess.DEVNULL, capture_output=True, text=True, cwd=work)
    row = {"engine": "lammps" if args.plugin is None else "plugin",
           "scheme": "vv (fix nve)" if args.plugin is None else args.scheme,
           "ranks": args.ranks, "dt": args.dt, "skin": args.skin}
    loops = re.findall(r"Loop time of (\S+) on \d+ procs for (\d+) steps with (\d+) atoms", out.stdout)
    if out.returncode != 0 or len(loops) != 2:
        lines = (out.stdout + out.stderr).strip().splitlines()
        errors = [line for line in lines if "ERROR" in line] or lines[-1:]
        print(json.dumps(dict(row, error=errors[0] if errors else f"exit {out.returncode}")))
        return
    seconds, steps, atoms = float(loops[1][0]), int(loops[1][1]), int(loops[1][2])
    # The timed run's thermo rows "STEP TEMP PRESS", between its header and its loop time.
    timed = out.stdout[:out.stdout.rindex("Loop time of")].rsplit("Step", 1)[1].splitlines()
    rows = [list(map(float, line.split()[:3])) for line in timed if line.split()[:1] and line.split()[0].isdigit()]
    row.update(n=atoms, us_per_step=round(seconds / steps * 1e6, 1),
               ns_per_particle_step=round(seconds / (steps * atoms) * 1e9, 1),
               temp=rows[-1][1], press=rows[-1][2])
    if args.thermo and len(rows) > 1:
        # Means over the rows after the first, with the standard error of 10 block means.
        for k, name in ((1, "temp"), (2, "press")):
            values = [r[k] for r in rows[1:]]
            size = len(values) // 10
            blocks = [statistics.fmean(values[b * size:(b + 1) * size]) for b in range(10)] if size else []
            row[name + "_mean"] = statistics.fmean(values)
            row[name + "_se"] = statistics.stdev(blocks) / len(blocks) ** 0.5 if blocks else None
    print(json.dumps(row))


if __name__ == "__main__":
    main()
