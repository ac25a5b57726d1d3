#!/usr/bin/env python3
"""Checks of the LAMMPS plugin `fix dpd/split` (docs/lammps.md), driven by
scripts/test-lammps.sh. Standard library only.

Evidence (each check states its tolerance where it defines it):
- equilibrium: plugin ABOBA, BAOAB, OBABO, S(x1) S(x0) S(x1) O and VV on 1 and 2 ranks against
  `dpd run` on the same scene (standard box, gamma = 4.5) in T_K and pressure;
- the plugin's VV against LAMMPS's own pair dpd + fix nve;
- bitwise repeat at a fixed rank count; total momentum on 1, 2 and 4 ranks;
- bad input: LAMMPS errors naming the problem, never a crash; exporter refusals.
"""

import argparse
import json
import math
import os
import subprocess
import sys

# The scene: the standard box of algorithms.md section 8 (density 3, a = 25, gamma = 4.5,
# k_B T = 1, r_c = 1, m = 1) with N = 3000 (L = 10, so two and four ranks keep subdomain sides
# of 5 >= 4 r_c + 2 skin = 4.6).
N = 3000
DENSITY = 3.0
GAMMA = 4.5
SKIN = 0.4

FAILURES = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        FAILURES.append(what)


def box_side(n):
    return (n / DENSITY) ** (1.0 / 3.0)


def lammps_input(plugin, integrator, steps, dt, thermo, seed=2024, n=N, side=None, extra=""):
    """An input for the standard box: `integrator` is the fix line(s) (and pair coefficients)."""
    side = side or box_side(n)
    return f"""
units lj
atom_style atomic
comm_modify vel yes
region box block 0 {side!r} 0 {side!r} 0 {side!r}
create_box 1 box
create_atoms 1 random {n} {seed} NULL
mass 1 1.0
neighbor {SKIN} bin
neigh_modify every 1 delay 0 check yes
timestep {dt!r}
velocity all create 1.0 {seed + 1} mom yes dist gaussian
plugin load {plugin}
{integrator}
{extra}
variable px equal mass(all)*vcm(all,x)
variable py equal mass(all)*vcm(all,y)
variable pz equal mass(all)*vcm(all,z)
thermo_style custom step temp press v_px v_py v_pz
thermo_modify format float %.17g norm no
thermo {thermo}
run {steps}
"""


def plugin_fix(scheme, seed=4321):
    return (f"pair_style dpd 1.0 1.0 999\npair_coeff 1 1 25.0 0.0 1.0\n"
            f"fix 1 all dpd/split {scheme} 1.0 {GAMMA} 1.0 {seed}")


def native_vv(seed=4321):
    return (f"pair_style dpd 1.0 1.0 {seed}\npair_coeff 1 1 25.0 {GAMMA} 1.0\n"
            "fix 1 all nve")


def run_lammps(args, text, ranks, name):
    path = os.path.join(args.work, name + ".in")
    with open(path, "w") as f:
        f.write(text)
    cmd = [args.mpirun, "-np", str(ranks), args.lmp, "-in", path, "-log", "none"]
    out = subprocess.run(cmd, capture_output=True, text=True, cwd=args.work, timeout=600)
    return out.returncode, out.stdout + out.stderr


def thermo_rows(output):
    rows, on = [], False
    for line in output.splitlines():
        words = line.split()
        if words[:2] == ["Step", "Temp"]:
            on = True
            continue
        if on and words and words[0] == "Loop":
            on = False
            continue
        if on and len(words) == 6:
            rows.append([float(w) for w in words])
    return rows


def mean_and_error(values, blocks=10):
    """Mean and its standard error from `blocks` block averages (blocks longer than the
    correlation time of T_K and P in the standard box, ~1 time unit, so nearly independent)."""
    size = len(values) // blocks
    means = [sum(values[k * size:(k + 1) * size]) / size for k in range(blocks)]
    m = sum(means) / blocks
    var = sum((x - m) ** 2 for x in means) / (blocks - 1)
    return m, math.sqrt(var / blocks)


def dpd_run(args, scheme, dt, time, runs):
    cmd = [args.dpd, "run", "--scheme", scheme, "--gamma", str(GAMMA), "--n", str(N),
           "--dt", str(dt), "--time", str(time), "--runs", str(runs), "--json"]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
    if out.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed: {out.stderr}")
    results = json.loads(out.stdout)["results"]
    stats = {}
    for key in ("kinetic_temperature", "pressure"):
        values = [r[key] for r in results]
        m = sum(values) / len(values)
        var = sum((x - m) ** 2 for x in values) / (len(values) - 1)
        stats[key] = (m, math.sqrt(var / len(values)))
    return stats


def agree(a, b, sigmas=4.0):
    """Means (m, se) agree within `sigmas` combined standard errors: with ~30 comparisons a
    correct plugin fails one by chance with probability ~30 * 6e-5 = 2e-3."""
    return abs(a[0] - b[0]) <= sigmas * math.hypot(a[1], b[1])


def equilibrium(args):
    dt, equil, steps, thermo = args.dt, args.equilibrate, args.steps, 10
    schemes = [("aboba", "aboba"), ("baoab", "baoab"), ("obabo", "obabo"),
               ("S(x1) S(x0) S(x1) O", "s_x1_s_x0_s_x1_o"), ("vv", "vv")]
    time = dt * steps
    for scheme, ident in schemes:
        ref = dpd_run(args, scheme, dt, time + dt * equil, args.dpd_runs)
        for ranks in (1, 2):
            text = lammps_input(args.plugin, plugin_fix(ident), equil + steps, dt, thermo)
            code, out = run_lammps(args, text, ranks, f"eq-{ident}-{ranks}")
            if code != 0:
                check(False, f"{scheme} on {ranks} rank(s) ran: {out[-2000:]}")
                continue
            rows = [r for r in thermo_rows(out) if r[0] > equil]
            for col, key in ((1, "kinetic_temperature"), (2, "pressure")):
                mine = mean_and_error([r[col] for r in rows])
                theirs = ref[key]
                check(agree(mine, theirs),
                      f"{scheme} dt={dt} {ranks} rank(s): {key} plugin {mine[0]:.4f} +- {mine[1]:.4f}"
                      f" vs dpd run {theirs[0]:.4f} +- {theirs[1]:.4f}")
    # The plugin's VV against LAMMPS's own velocity Verlet DPD (pair dpd + fix nve).
    for ranks in (1, 2):
        results = []
        for name, fix in (("plugin", plugin_fix("vv")), ("native", native_vv())):
            text = lammps_input(args.plugin, fix, equil + steps, dt, thermo)
            code, out = run_lammps(args, text, ranks, f"vv-{name}-{ranks}")
            rows = [r for r in thermo_rows(out) if r[0] > equil]
            results.append([mean_and_error([r[c] for r in rows]) for c in (1, 2)] if code == 0 else None)
        if None in results:
            check(False, f"VV plugin and native on {ranks} rank(s) ran")
            continue
        for k, key in enumerate(("T_K", "pressure")):
            a, b = results[0][k], results[1][k]
            check(agree(a, b), f"VV {ranks} rank(s) {key}: plugin {a[0]:.4f} +- {a[1]:.4f} vs "
                               f"pair dpd + fix nve {b[0]:.4f} +- {b[1]:.4f}")


def repeat_and_momentum(args):
    dt, steps = args.dt, 200
    for ident in ("aboba", "vv"):
        text = lammps_input(args.plugin, plugin_fix(ident), steps, dt, 20)
        for ranks in (1, 2):
            outs = [run_lammps(args, text, ranks, f"rep-{ident}-{ranks}-{k}") for k in range(2)]
            rows = [thermo_rows(o) for _, o in outs]
            check(outs[0][0] == 0 and rows[0] and rows[0] == rows[1],
                  f"{ident} on {ranks} rank(s) repeats bitwise ({len(rows[0])} thermo rows of 17 digits)")
        for ranks in (1, 2, 4):
            code, out = run_lammps(args, text, ranks, f"mom-{ident}-{ranks}")
            rows = thermo_rows(out)
            # Round-off: each of ~10^7 pair updates changes the total by ~1e-16 |p|, at random;
            # a lost ghost update changes it by ~0.1 at once. Tolerance 1e-9 per unit of
            # sqrt(N m k_B T) ~ 55.
            worst = max((math.sqrt(r[3] ** 2 + r[4] ** 2 + r[5] ** 2) for r in rows), default=float("inf"))
            check(code == 0 and worst < 1e-9 * math.sqrt(N),
                  f"{ident} on {ranks} rank(s): total momentum stays below {1e-9 * math.sqrt(N):.1e} (max {worst:.2e})")


def bad_input(args):
    cases = [
        ("unknown scheme", "fix 1 all dpd/split abobq 1.0 4.5 1.0 4321", "scheme 'abobq' is not compiled"),
        ("scheme not compiled in", "fix 1 all dpd/split baooab 1.0 4.5 1.0 4321", "scheme 'baooab' is not compiled"),
        ("too few arguments", "fix 1 all dpd/split aboba 1.0 4.5", "expected fix ID group dpd/split SCHEME"),
        ("not a number", "fix 1 all dpd/split aboba one 4.5 1.0 4321", "kT = 'one' is not a finite number"),
        ("negative gamma", "fix 1 all dpd/split aboba 1.0 -4.5 1.0 4321", "gamma"),
        ("bad seed", "fix 1 all dpd/split aboba 1.0 4.5 1.0 -3", "seed = '-3' must be a positive integer"),
        ("unknown keyword", "fix 1 all dpd/split aboba 1.0 4.5 1.0 4321 exponant 1", "unknown keyword 'exponant'"),
        ("r_c beyond the pair cutoff", "fix 1 all dpd/split aboba 1.0 4.5 1.5 4321", "exceeds the pair style's cutoff"),
    ]
    for what, fix, message in cases:
        text = lammps_input(args.plugin, "pair_style dpd 1.0 1.0 999\npair_coeff 1 1 25.0 0.0 1.0\n" + fix, 10, 0.04, 10, n=300)
        code, out = run_lammps(args, text, 1, "bad")
        crashed = "signal" in out.lower() or "segmentation" in out.lower()
        check(code != 0 and message in out and not crashed, f"bad input, {what}: LAMMPS error containing {message!r}")
    small = lammps_input(args.plugin, plugin_fix("aboba"), 10, 0.04, 10, n=150, side=4.0)
    code, out = run_lammps(args, small, 1, "small")
    check(code != 0 and "is below 4 r_c + 2 skin" in out, "a box of side 4 on 1 rank is refused (below 4 r_c + 2 skin)")
    for names, message in ((["setd"], "hand-written"), (["A B(1/2) O"], "--allow-inconsistent"),
                           (["abobq"], "unknown scheme 'abobq'"), (["sas"], "T stage")):
        out = subprocess.run([args.dpd, "export", "lammps", *names, "--out", os.path.join(args.work, "refused")],
                             capture_output=True, text=True)
        check(out.returncode == 2 and message in out.stderr, f"dpd export lammps {names[0]!r} refused: {message!r}")


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--lmp", required=True)
    p.add_argument("--mpirun", required=True)
    p.add_argument("--plugin", required=True)
    p.add_argument("--dpd", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--dt", type=float, default=0.08)
    p.add_argument("--equilibrate", type=int, default=200)
    p.add_argument("--steps", type=int, default=2000)
    p.add_argument("--dpd-runs", type=int, default=4)
    p.add_argument("--only", choices=["equilibrium", "repeat", "bad"], action="append")
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    parts = {"bad": bad_input, "repeat": repeat_and_momentum, "equilibrium": equilibrium}
    for name in args.only or ["bad", "repeat", "equilibrium"]:
        parts[name](args)
    if FAILURES:
        print(f"{len(FAILURES)} check(s) failed", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
