#!/usr/bin/env bash
# Trajectory files read back by the field's own readers (issues 27 and 48): `dpd run` writes GSD,
# extended XYZ and LAMMPS dump text; the `gsd` package reads every GSD frame (N, box, step, time,
# dt, positions, velocities, images), ASE and MDAnalysis read the extended XYZ and the LAMMPS
# dump (positions, type names, velocities, time) and must agree with GSD to the precision of its
# f32; MDAnalysis reads the GSD file too; a run killed with SIGKILL mid-way leaves a GSD file that
# gsd reads whole; `--init` continues a frame's step, time and images (`--init-reset` starts
# them at 0). The readers live in a virtual environment under
# ${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}/trajectory (reused if present).
set -euo pipefail
cd "$(dirname "$0")/.."
venv="${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}/trajectory"
bash scripts/venvs.sh trajectory
# The binary `cargo test --workspace` built (optimised test profile); built here only if absent.
[ -x target/debug/dpd ] || cargo build --quiet -p dpd-cli
dpd="$PWD/target/debug/dpd"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
# 300 particles, dt = 0.05, 2 time units: 40 steps, a frame every 10 steps, 5 frames.
run=(run --n 300 --time 2 --dt 0.05 --seed 3)
for file in t.gsd t.xyz t.lammpstrj; do
    "$dpd" "${run[@]}" --trajectory "$file" --every 0.5 >/dev/null 2>&1
done
# The same run with a frame every step, to check the images against each step's displacement.
"$dpd" "${run[@]}" --trajectory steps.gsd --every 0.05 >/dev/null 2>&1
# Frame 2 (step 20) as the start of a 10-step run whose first frame must be that state, with
# the frame's step, time and images; and again with the counters reset.
"$dpd" run --n 300 --time 0.5 --dt 0.05 --init t.gsd:2 --trajectory init.gsd --every 0.5 \
    >/dev/null 2>&1
"$dpd" run --n 300 --time 0.5 --dt 0.05 --init t.gsd:2 --init-reset --trajectory reset.gsd \
    --every 0.5 >/dev/null 2>&1
# Errors name what is wrong: frame out of range, missing file, particle count.
expect_error() {
    if "$dpd" "$@" >/dev/null 2>err.txt; then
        echo "accepted: dpd $*"; exit 1
    fi
}
expect_error run --n 300 --init t.gsd:5
grep -q "frame 5 is out of range: the file has 5 frames" err.txt || { cat err.txt; exit 1; }
expect_error run --n 300 --init none.gsd
grep -q "none.gsd" err.txt || { cat err.txt; exit 1; }
expect_error run --n 400 --init t.gsd
grep -q "has 300 particles, the scene 400" err.txt || { cat err.txt; exit 1; }
# A long run killed once its file has frames: every committed frame must read back.
"$dpd" run --n 1500 --time 10000 --trajectory killed.gsd --every 0.05 >/dev/null 2>&1 &
pid=$!
for _ in $(seq 100); do
    [ "$(stat -c %s killed.gsd 2>/dev/null || echo 0)" -gt 200000 ] && break
    sleep 0.1
done
kill -9 "$pid"
wait "$pid" 2>/dev/null || true
"$venv/bin/python" - <<'PY'
import gsd.hoomd
import numpy as np
import ase.io

with gsd.hoomd.open("t.gsd") as t:
    frames = list(t)
assert len(frames) == 5, len(frames)
L = 300 / 3.0
for k, f in enumerate(frames):
    assert f.configuration.step == 10 * k, f.configuration.step
    assert f.log["dt"].item() == 0.05 and abs(f.log["time"].item() - 0.5 * k) < 1e-12, f.log
    assert f.particles.N == 300
    box = f.configuration.box
    assert np.allclose(box[:3], L ** (1 / 3), rtol=1e-6) and not box[3:].any(), box
    half = box[:3] / 2
    assert (f.particles.position >= -half).all() and (f.particles.position < half).all()
    assert f.particles.types == ["A"] and (f.particles.typeid == 0).all()
    assert sorted(f.log) == ["configurational_temperature", "dt", "kinetic_temperature",
                             "potential_energy", "pressure", "time"], f.log
    logs = dict(f.log)
    t_c = logs.pop("configurational_temperature")
    assert all(np.isfinite(v).all() for v in logs.values()), f.log
    # T_C is undefined (NaN) where the Laplacian sum is not positive, as at this random start.
    if k == 0:
        assert np.isnan(t_c).all(), t_c
    if k == len(frames) - 1:
        assert np.isfinite(t_c).all() and 0.5 < t_c[0] < 2.0, t_c

# ASE reads the text formats; their positions (written from f64) agree with GSD's f32 values
# to f32's resolution at the box edge, so the three runs are the same trajectory.
for name, fmt in [("t.xyz", "extxyz"), ("t.lammpstrj", "lammps-dump-text")]:
    atoms = ase.io.read(name, index=":", format=fmt)
    assert len(atoms) == 5, (name, len(atoms))
    for a, f in zip(atoms, frames):
        assert len(a) == 300
        assert np.allclose(a.cell.lengths(), f.configuration.box[:3], rtol=1e-6)
        centred = a.get_positions() - f.configuration.box[:3] / 2
        assert np.abs(centred - f.particles.position).max() < 1e-5, name
# The extended XYZ's time, dt, masses and velocities as ASE reads them (get_velocities is
# momenta / masses: with no masses column it divides by hydrogen's 1.008).
for a, f in zip(ase.io.read("t.xyz", index=":"), frames):
    assert (a.info["step"], a.info["time"], a.info["dt"]) == (
        f.configuration.step, f.log["time"].item(), f.log["dt"].item()), a.info
    assert (a.get_masses() == 1.0).all()
    assert np.abs(a.get_velocities() - f.particles.velocity).max() < 1e-5

# MDAnalysis: the type name and the positions of the extended XYZ (its plain-XYZ reader takes
# the first four columns), the dump's positions, velocities and time (step x the dt it is
# given), the GSD positions and step.
import MDAnalysis as mda
import warnings
warnings.simplefilter("ignore")  # MDAnalysis warns of the masses it guesses from type names
xyz = mda.Universe("t.xyz")
dump = mda.Universe("t.lammpstrj", format="LAMMPSDUMP", dt=0.05)
hoomd = mda.Universe("t.gsd")
assert len(xyz.trajectory) == len(dump.trajectory) == len(hoomd.trajectory) == 5
assert set(xyz.atoms.names) == {"A"}
for f, _, _, _ in zip(frames, xyz.trajectory, dump.trajectory, hoomd.trajectory):
    half = f.configuration.box[:3] / 2
    assert np.abs(xyz.atoms.positions - half - f.particles.position).max() < 1e-4
    assert np.abs(dump.atoms.positions - half - f.particles.position).max() < 1e-4
    assert np.abs(dump.atoms.velocities - f.particles.velocity).max() < 1e-5
    assert abs(dump.trajectory.ts.time - f.log["time"].item()) < 1e-9, dump.trajectory.ts.time
    assert np.abs(hoomd.atoms.positions - f.particles.position).max() < 1e-6
    assert hoomd.trajectory.ts.data["step"] == f.configuration.step
    # MDAnalysis 2.11's GSD reader takes positions and box only (its _read_frame), whatever
    # the file holds: docs/trajectories.md says so, and this notices a version that reads more.
    assert not hoomd.trajectory.ts.has_velocities

# Images: between two steps a particle moves much less than half an edge, so its displacement
# is the minimum image of the change of its wrapped position; the images must turn the wrapped
# change into that displacement, and the 10-step files must hold the same images.
with gsd.hoomd.open("steps.gsd") as t:
    steps = list(t)
assert len(steps) == 41, len(steps)
edge = steps[0].configuration.box[:3]
crossed = 0
for a, b in zip(steps, steps[1:]):
    change = b.particles.position - a.particles.position
    nearest = change - edge * np.round(change / edge)
    unwrapped = change + (b.particles.image - a.particles.image) * edge
    assert np.abs(unwrapped - nearest).max() < 1e-4, a.configuration.step
    crossed += np.abs(b.particles.image - a.particles.image).sum()
assert crossed > 0, "no particle crossed a face: the check checked nothing"
for f in frames:
    assert (f.particles.image == steps[f.configuration.step].particles.image).all()

with gsd.hoomd.open("init.gsd") as t:
    start, end = t[0], t[-1]
assert (start.configuration.step, end.configuration.step) == (20, 30)
assert abs(start.log["time"].item() - 1.0) < 1e-12 and abs(end.log["time"].item() - 1.5) < 1e-12
assert (start.particles.image == frames[2].particles.image).all()
assert np.abs(start.particles.position - frames[2].particles.position).max() < 1e-5
assert np.abs(start.particles.velocity - frames[2].particles.velocity).max() < 1e-5
with gsd.hoomd.open("reset.gsd") as t:
    reset = t[0]
assert (reset.configuration.step, reset.log["time"].item()) == (0, 0.0)
assert not reset.particles.image.any()
assert np.abs(reset.particles.position - frames[2].particles.position).max() < 1e-5

with gsd.hoomd.open("killed.gsd") as t:
    n = len(t)
    assert n >= 2, n
    for f in t:
        assert f.particles.N == 1500 and np.isfinite(f.particles.position).all()
print(f"trajectory readers: 5 frames each of GSD, extended XYZ and LAMMPS dump agree in gsd, "
      f"ASE and MDAnalysis; images follow {crossed} face crossings in 40 steps; --init "
      f"continues frame 2's step, time and images, --init-reset restarts them; "
      f"the killed run's {n} frames read back")
PY
