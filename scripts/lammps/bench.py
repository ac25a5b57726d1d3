#!/usr/bin/env python3
"""Side-by-side cost of DPD integrators in LAMMPS (docs/performance.md; a benchmark, not a
test): wall ns per particle-step of the plugin's ABOBA and VV (`fix dpd/split`; the conservative
force from pair dpd at zero friction, a pair table or the plugin's pair dpd/soft), LAMMPS's own
velocity Verlet (`pair dpd` + `fix nve`) and Shardlow splitting (`pair dpd/fdt` + `fix
shardlow` + `fix nve`, package DPD-REACT), on the standard box (density 3, a = 25, gamma = 4.5,
k_B T = 1, r_c = 1, skin 0.4, dt = 0.04) at each N and rank count. The time is LAMMPS's loop
time of the timed run, after a warm-up run (setup excluded). With `--cpu`, also the CPU time
per particle-step, summed over the ranks: the difference between a run with the timed steps
twice and one with them once, each measured as the CPU time of the child processes
(getrusage), so that, unlike wall time, it leaves out the time spent waiting for a core on a
loaded machine. With `--timers`, also LAMMPS's timer breakdown of the timed run (the average
over the ranks of Pair, Neigh, Comm, Output, Modify and Other), in wall ns per particle-step.
Standard library only.

    python3 scripts/lammps/bench.py --lmp VENV/bin/lmp --mpirun VENV/bin/mpirun \\
        --plugin PLUGIN.so --work DIR [--n 24000] [--ranks 1 --ranks 2] [--steps 200]
        [--warmup 200] [--variant NAME]... [--thermo N] [--thermo-style "custom step temp"] [--cpu]
        [--timers]
"""

import argparse
import os
import re
import resource
import subprocess

GAMMA, KT, A = 4.5, 1.0, 25.0
SIGMA = (2.0 * GAMMA * KT) ** 0.5

# Ghost velocities for the styles that read them (pair dpd, pair dpd/fdt, fix shardlow); the
# plugin's fix communicates its own, so with a conservative style alone it needs none.
VEL = "comm_modify vel yes\n"

# name -> (atom style, force field and integrator lines)
VARIANTS = {
    "plugin ABOBA": ("atomic", VEL + "pair_style dpd 1.0 1.0 999\npair_coeff 1 1 {a} 0.0 1.0\n"
                               "fix 1 all dpd/split aboba {kt} {gamma} 1.0 4321"),
    "plugin VV": ("atomic", VEL + "pair_style dpd 1.0 1.0 999\npair_coeff 1 1 {a} 0.0 1.0\n"
                            "fix 1 all dpd/split vv {kt} {gamma} 1.0 4321"),
    # The conservative force from a table instead of pair dpd, which draws a random number per
    # pair even at gamma = 0: the DPD force is linear in r, so a fine table is exact to ~1e-7.
    "plugin ABOBA, pair table": ("atomic", "pair_style table linear 1000\n"
                                           "pair_coeff 1 1 dpd.table DPD 1.0\n"
                                           "fix 1 all dpd/split aboba {kt} {gamma} 1.0 4321"),
    # The plugin's own conservative style: pair dpd's force without its friction and noise.
    "plugin ABOBA, pair dpd/soft": ("atomic", "pair_style dpd/soft 1.0\npair_coeff 1 1 {a}\n"
                                              "fix 1 all dpd/split aboba {kt} {gamma} 1.0 4321"),
    "pair dpd + fix nve": ("atomic", VEL + "pair_style dpd {kt} 1.0 4321\n"
                                     "pair_coeff 1 1 {a} {gamma} 1.0\nfix 1 all nve"),
    "fix shardlow": ("dpd", VEL + "pair_style dpd/fdt {kt} 1.0 4321\npair_coeff 1 1 {a} {sigma} 1.0\n"
                            "fix 1 all shardlow\nfix 2 all nve"),
}


def write_table(path, points=1000):
    """The DPD conservative pair force a (1 - r) and energy a (1 - r)^2 / 2 (r_c = 1) as a
    LAMMPS pair table, keyword DPD."""
    with open(path, "w") as f:
        f.write(f"# DPD conservative force, a = {A}, r_c = 1\n\nDPD\nN {points} R 0.001 1.0\n\n")
        for k in range(points):
            r = 0.001 + 0.999 * k / (points - 1)
            f.write(f"{k + 1} {r!r} {A * 0.5 * (1 - r) ** 2!r} {A * (1 - r)!r}\n")


def lammps_input(plugin, style, lines, n, steps, warmup, thermo=None, thermo_style="one"):
    side = (n / 3.0) ** (1.0 / 3.0)
    body = lines.format(a=A, kt=KT, gamma=GAMMA, sigma=SIGMA)
    return f"""units lj
atom_style {style}
region box block 0 {side!r} 0 {side!r} 0 {side!r}
create_box 1 box
create_atoms 1 random {n} 2024 NULL
mass 1 1.0
neighbor 0.4 bin
neigh_modify every 1 delay 0 check yes
timestep 0.04
velocity all create 1.0 2025 mom yes dist gaussian
plugin load {plugin}
{body}
thermo_style {thermo_style}
thermo {thermo or steps}
run {warmup}
run {steps}
"""


def run(args, path, ranks):
    """LAMMPS on `path` with `ranks` ranks: its output and the CPU seconds its processes used."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run([args.mpirun, "-np", str(ranks), args.lmp, "-in", path, "-log", "none"],
                         capture_output=True, text=True, cwd=args.work)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return out, (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)


SECTIONS = ("Pair", "Neigh", "Comm", "Output", "Modify", "Other")


def timers(stdout, steps, atoms):
    """The average time of each of LAMMPS's timer sections in the last run's breakdown, in ns per
    particle-step, as "Pair 123 / Neigh 456 / ..." (sections it does not print left out)."""
    table = stdout.rsplit("MPI task timing breakdown", 1)[-1]
    cells = []
    for name in SECTIONS:
        row = re.search(rf"^{name}\s*\|[^|]*\|\s*(\S+)", table, re.MULTILINE)
        if row:
            cells.append(f"{name} {float(row.group(1)) / steps / atoms * 1e9:.0f}")
    return " / ".join(cells)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    for name in ("--lmp", "--mpirun", "--plugin", "--work"):
        p.add_argument(name, required=True)
    p.add_argument("--n", type=int, action="append")
    p.add_argument("--ranks", type=int, action="append")
    p.add_argument("--steps", type=int, default=200)
    # Steps run before the timed run: the random start's overlaps relax and the neighbour-list
    # rebuild rate settles (every 1.6 steps at dt = 0.04 and skin 0.4).
    p.add_argument("--warmup", type=int, default=200)
    p.add_argument("--variant", choices=list(VARIANTS), action="append")
    # Thermo output (LAMMPS's default style: temperature, energies, pressure) every this many
    # steps of the timed run (default: its first and last step only).
    p.add_argument("--thermo", type=int)
    # Its columns: LAMMPS's default `one` (temperature, pair and molecular energy, total
    # energy, pressure: energy and virial tallied on those steps), or e.g. `custom step temp`.
    p.add_argument("--thermo-style", default="one")
    p.add_argument("--cpu", action="store_true", help="also CPU ns per particle-step (see above)")
    p.add_argument("--timers", action="store_true", help="also LAMMPS's timer sections (see above)")
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    write_table(os.path.join(args.work, "dpd.table"))
    unit = "ns/particle-step" + (" (wall, CPU)" if args.cpu else "")
    print("| N | variant | " + " | ".join(f"{r} rank(s): {unit}" for r in args.ranks or [1, 2]) + " |")
    for n in args.n or [24000]:
        for name in args.variant or list(VARIANTS):
            style, lines = VARIANTS[name]
            paths = []
            for steps in (args.steps, 2 * args.steps)[:2 if args.cpu else 1]:
                paths.append(os.path.join(args.work, f"bench-{steps}.in"))
                with open(paths[-1], "w") as f:
                    f.write(lammps_input(args.plugin, style, lines, n, steps, args.warmup, args.thermo,
                                         args.thermo_style))
            cells = []
            for ranks in args.ranks or [1, 2]:
                out, cpu = run(args, paths[0], ranks)
                loops = re.findall(r"Loop time of (\S+) on \d+ procs for (\d+) steps with (\d+) atoms", out.stdout)
                if out.returncode != 0 or len(loops) != 2:
                    cells.append("failed: " + (out.stdout + out.stderr).strip().splitlines()[-1])
                    continue
                seconds, steps, atoms = float(loops[1][0]), int(loops[1][1]), int(loops[1][2])
                cell = f"{seconds / steps / atoms * 1e9:.0f}"
                if args.timers:
                    cell += f" ({timers(out.stdout, steps, atoms)})"
                if args.cpu:
                    twice, cpu2 = run(args, paths[1], ranks)
                    cell += f", {(cpu2 - cpu) / steps / atoms * 1e9:.0f}" if twice.returncode == 0 else ", failed"
                cells.append(cell)
            print(f"| {n} | {name} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
