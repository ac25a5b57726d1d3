"""Species, bonds and molecules from Python, against the scene and data files that make them."""

from pathlib import Path
from typing import Any

import numpy as np
import pytest

import dpd

SCENES = Path(__file__).resolve().parents[2] / "scenes"

PAIRS = {"A-A": {"a": 25.0}, "B-B": {"a": 25.0}, "A-B": {"a": 40.0}}


def _mixture(**keys: Any) -> dpd.Simulation:
    """A 1:3 mixture of A (mass 2) and B (mass 1)."""
    species = [{"name": "A", "fraction": 0.25, "mass": 2.0}, {"name": "B", "fraction": 0.75}]
    return dpd.Simulation(species=species, pairs=PAIRS, **keys)


def test_a_mixture_s_particles_have_their_species_types_and_masses():
    # The first N_A ids are A, the rest B (docs/systems.md), and row i stays particle i after
    # steps that re-sort the storage at every neighbour rebuild.
    sim = _mixture(n=400, seed=2, threads=1)
    assert sim.types == ["A", "B"]
    t = sim.typeid
    assert t.shape == (400,) and t.dtype == np.int64
    assert np.array_equal(t, np.repeat([0, 1], [100, 300]))
    assert np.array_equal(sim.masses, np.where(t == 0, 2.0, 1.0))
    sim.run(steps=60)
    assert np.array_equal(sim.typeid, t)
    assert np.array_equal(sim.masses, np.where(t == 0, 2.0, 1.0))
    # k_B T_K = sum m v.v / 3 (N - 1) with each particle's own mass: masses and velocities
    # by the same id, or a heavy A would be paired with a light B's velocity.
    v = sim.velocities
    tk = np.sum(sim.masses[:, None] * v * v) / (3 * (400 - 1))
    assert tk == pytest.approx(sim.observables()["kinetic_temperature"], rel=1e-12)
    assert sim.bonds.shape == (0, 2) and sim.angles.shape == (0, 3)
    assert sim.bond_typeid.shape == (0,) and sim.bond_types == [] and sim.chains == []


def test_a_scene_file_with_species_loads():
    sim = dpd.Simulation(scene=SCENES / "mixture.toml", threads=1)
    assert sim.types == ["A", "B"]
    assert np.bincount(sim.typeid).tolist() == [1536, 1536]
    assert np.all(sim.masses == 1.0)


def _read_xyz(path: Path) -> tuple[list[str], np.ndarray, np.ndarray]:
    """Species, positions and masses of the first frame of an extended XYZ file."""
    lines = path.read_text().splitlines()
    n = int(lines[0])
    props = lines[1].split("Properties=")[1].split()[0].split(":")
    column: dict[str, int] = {}
    at = 0
    for k in range(0, len(props), 3):
        column[props[k]] = at
        at += int(props[k + 2])
    rows = [line.split() for line in lines[2:2 + n]]
    species = [r[column["species"]] for r in rows]
    q = np.array([[float(x) for x in r[column["pos"]:column["pos"] + 3]] for r in rows])
    m = np.array([float(r[column["mass"]]) for r in rows])
    return species, q, m


def test_the_types_are_those_of_the_trajectory(tmp_path):
    # The trajectory writer (the same as `dpd run --trajectory`) names each particle's species
    # in its own pass over the system: row by row the same names, positions and masses.
    sim = _mixture(n=200, seed=4, threads=1)
    sim.run(steps=30)
    sim.trajectory(tmp_path / "t.xyz", every=1.0)
    sim.trajectory(None)
    species, q, m = _read_xyz(tmp_path / "t.xyz")
    assert species == [sim.types[t] for t in sim.typeid]
    assert np.allclose(q, sim.positions, rtol=0, atol=1e-9)
    assert np.array_equal(m, sim.masses)


DATA = """types and positions by atom id, out of order

4 atoms
2 atom types

0 4 xlo xhi
0 4 ylo yhi
0 4 zlo zhi

Atom Type Labels

1 A
2 B

Masses

1 1.5
2 0.5

PairIJ Coeffs # dpd

1 1 25 4.5 1
1 2 30 4.5 1
2 2 25 4.5 1

Atoms # atomic

3 2 1.5 0.5 0.5
1 1 0.25 0.25 0.25
4 1 1.0 1.75 1.0
2 2 0.5 1.5 1.5
"""


def test_a_data_file_gives_types_masses_and_positions_by_atom_id(tmp_path):
    path = tmp_path / "four.data"
    path.write_text(DATA)
    sim = dpd.Simulation(init=str(path), box=[4.0, 4.0, 4.0], density=4 / 64, threads=1)
    assert sim.types == ["A", "B"]
    assert sim.typeid.tolist() == [0, 1, 1, 0]
    assert sim.masses.tolist() == [1.5, 0.5, 0.5, 1.5]
    want = [[0.25, 0.25, 0.25], [0.5, 1.5, 1.5], [1.5, 0.5, 0.5], [1.0, 1.75, 1.0]]
    assert sim.positions.tolist() == want
