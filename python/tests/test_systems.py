"""Species, bonds and molecules from Python, against the scene and data files that make them."""

from pathlib import Path
from typing import Any

import numpy as np
import pytest

import dpd

SCENES = Path(__file__).resolve().parents[2] / "scenes"

PAIRS = {"A-A": {"a": 25.0}, "B-B": {"a": 25.0}, "A-B": {"a": 40.0}}


def _mixture(pairs: dict[str, Any] = PAIRS, **keys: Any) -> dpd.Simulation:
    """A 1:3 mixture of A (mass 2) and B (mass 1)."""
    species = [{"name": "A", "fraction": 0.25, "mass": 2.0}, {"name": "B", "fraction": 0.75}]
    return dpd.Simulation(species=species, pairs=pairs, **keys)


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


def _block_ratio_error(num: np.ndarray, den: np.ndarray, blocks: int) -> float:
    """Standard error of sum(num) / sum(den) from the ratios of equal blocks' sums."""
    skip = len(num) % blocks
    ratios = num[skip:].reshape(blocks, -1).sum(axis=1) / den[skip:].reshape(blocks, -1).sum(axis=1)
    return float(ratios.std(ddof=1) / np.sqrt(blocks))


def _pairs(q: np.ndarray, box: np.ndarray, r_max: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every pair i < j closer than r_max under minimum image: i, j, r."""
    d = q[:, None, :] - q[None, :, :]
    d -= box * np.round(d / box)
    r = np.sqrt((d**2).sum(axis=2))
    i, j = np.triu_indices(len(q), 1)
    close = r[i, j] < r_max
    return i[close], j[close], r[i, j][close]


def test_per_type_observables_are_what_sampling_by_hand_gives():
    # The same 40 samples taken by measure() and by hand from a restored snapshot: g_ij(r) from
    # numpy's histograms of each pair of types (N_i N_j / V per shell for unlike pairs,
    # N_i^2 / 2V for like ones, docs/systems.md), each type's like-neighbour counts within
    # r_c = 1 with their block error, and its slab densities along x, to rounding.
    sim = _mixture(n=300, seed=5, threads=1)
    sim.run(steps=40)
    snap = sim.snapshot()
    rdf, profile = {"r_max": 1.5, "bins": 15}, {"bins": 4, "axis": 0}
    m = sim.measure(80, every=0.1, blocks=4, rdf=rdf, profile=profile, like_neighbours=True)
    assert m.samples == 40 and m.bond_length is None and m.end_to_end_squared is None
    sim.restore(snap)
    pos = []
    for _ in range(40):
        sim.run(steps=2)
        pos.append(sim.positions)
    t, box = sim.typeid, np.array(sim.box_lengths)
    n_type = np.bincount(t)
    edges = np.linspace(0.0, 1.5, 16)
    shells = 4.0 / 3.0 * np.pi * (edges[1:] ** 3 - edges[:-1] ** 3)
    hist = {"A-A": np.zeros(15), "A-B": np.zeros(15), "B-B": np.zeros(15)}
    like, every = np.zeros((40, 2)), np.zeros((40, 2))
    slabs = np.zeros((2, 4))
    for s, q in enumerate(pos):
        i, j, r = _pairs(q, box, 1.5)
        ti, tj = np.minimum(t[i], t[j]), np.maximum(t[i], t[j])
        for key, (a, b) in {"A-A": (0, 0), "A-B": (0, 1), "B-B": (1, 1)}.items():
            hist[key] += np.histogram(r[(ti == a) & (tj == b)], bins=15, range=(0.0, 1.5))[0]
        near = r < 1.0
        for k in (0, 1):
            like[s, k] = 2 * np.sum(near & (ti == k) & (tj == k))
            every[s, k] = np.sum(near & (t[i] == k)) + np.sum(near & (t[j] == k))
        for k in (0, 1):
            slabs[k] += np.histogram(q[t == k, 0], bins=4, range=(0.0, box[0]))[0]
    assert m.pair_rdf is not None and sorted(m.pair_rdf) == ["A-A", "A-B", "B-B"]
    for key, (a, b) in {"A-A": (0, 0), "A-B": (0, 1), "B-B": (1, 1)}.items():
        pairs = 0.5 * n_type[a] ** 2 if a == b else n_type[a] * n_type[b]
        ideal = pairs / box.prod() * shells * 40
        assert np.allclose(m.pair_rdf[key][:, 1], hist[key] / ideal, rtol=1e-12), key
    assert m.like_neighbours is not None and sorted(m.like_neighbours) == ["A", "B"]
    for k, name in enumerate(("A", "B")):
        e = m.like_neighbours[name]
        assert e is not None and e.mean == pytest.approx(like[:, k].sum() / every[:, k].sum(), rel=1e-12)
        assert e.stderr == pytest.approx(_block_ratio_error(like[:, k], every[:, k], 4), rel=1e-9)
    assert m.species_profile is not None
    width = box[0] / 4
    for k, name in enumerate(("A", "B")):
        rows = m.species_profile[name]
        assert np.allclose(rows[:, 0], width * (np.arange(4) + 0.5), rtol=1e-12)
        assert np.allclose(rows[:, 1], slabs[k] / (40 * box.prod() / 4), rtol=1e-12)
    one = dpd.Simulation(n=100, threads=1).measure(10, rdf={"r_max": 1.5})
    assert one.pair_rdf is None and one.like_neighbours is None and one.species_profile is None


def test_an_ideal_mixture_s_like_neighbours_are_its_composition():
    # Every pair a = 25: the types are labels the configurations do not see (the masses 2 and 1
    # change the dynamics only), so the expected like fraction of type i is (N_i - 1) / (N - 1),
    # 99/399 for A and 299/399 for B. 400 time units sampled every 0.5 in 10 blocks of 40 (the
    # neighbourhood decorrelates within a few time units): the mean is within four standard
    # errors, which are under 0.005, so the fraction of all like pairs (0.625 for both) or of
    # unlike neighbours (0.75 for A) would fail.
    ideal = {"A-A": {"a": 25.0}, "B-B": {"a": 25.0}, "A-B": {"a": 25.0}}
    sim = _mixture(ideal, n=400, seed=6, threads=1, dt=0.04)
    sim.run(steps=250)
    m = sim.measure(10000, every=0.5, like_neighbours=True)
    assert m.like_neighbours is not None
    for name, want in (("A", 99 / 399), ("B", 299 / 399)):
        e = m.like_neighbours[name]
        assert e is not None and e.stderr is not None and e.stderr < 0.005, (name, e)
        assert abs(e.mean - want) < 4 * e.stderr, (name, e, want)


def test_measure_accumulates_a_running_average():
    # Two calls of 60 steps, the second with accumulate=True, are the one call of 120 steps
    # from the same (restored) state, bit for bit: every mean, error and array.
    sim = _mixture(n=200, seed=7, threads=1)
    sim.run(steps=20)
    snap = sim.snapshot()
    tables: dict[str, Any] = {
        "rdf": {"r_max": 1.5, "bins": 15}, "vacf": {"max_lag": 0.5, "origin_every": 2},
        "profile": {"bins": 4}, "like_neighbours": True,
    }
    first = sim.measure(60, every=0.1, blocks=4, **tables)
    both = sim.measure(60, blocks=4, accumulate=True)
    sim.restore(snap)
    whole = sim.measure(120, every=0.1, blocks=4, **tables)
    assert (first.samples, both.samples, whole.samples) == (30, 60, 60)
    for name in ("kinetic_temperature", "configurational_temperature", "potential_energy",
                 "pressure"):
        b, w = getattr(both, name), getattr(whole, name)
        assert (b.mean, b.stderr) == (w.mean, w.stderr), name
    assert both.diffusion == whole.diffusion
    for name in ("rdf", "vacf"):
        assert np.array_equal(getattr(both, name), getattr(whole, name)), name
    assert both.pair_rdf is not None and whole.pair_rdf is not None
    assert both.species_profile is not None and whole.species_profile is not None
    for key in ("A-A", "A-B", "B-B"):
        assert np.array_equal(both.pair_rdf[key], whole.pair_rdf[key]), key
    for key in ("A", "B"):
        assert np.array_equal(both.species_profile[key], whole.species_profile[key]), key
    assert both.like_neighbours is not None and whole.like_neighbours is not None
    for key in ("A", "B"):
        b, w = both.like_neighbours[key], whole.like_neighbours[key]
        assert b is not None and w is not None and (b.mean, b.stderr) == (w.mean, w.stderr)
    with pytest.raises(TypeError, match=r"accumulate=True\) goes on with the previous call's"):
        sim.measure(10, every=0.1, accumulate=True)
    assert sim.measure(10, blocks=4, accumulate=True).samples == 65
    sim.dt = 0.04
    with pytest.raises(ValueError, match="no samples to go on from"):
        sim.measure(10, accumulate=True)


def _melt(**keys: Any) -> dpd.Simulation:
    """Chains of 5 beads on harmonic springs K r^2 (K = 2, Groot-Warren's C = 4), with a
    cosine angle at each inner bead unless `angle_types=None`."""
    chain: dict[str, Any] = {"length": 5, "fraction": 1.0, "bond": "spring"}
    if keys.get("angle_types", True):
        chain["angle"] = "bend"
        keys.setdefault("angle_types", [{"name": "bend", "style": "cosine", "k": 1.5}])
    return dpd.Simulation(
        bond_types=[{"name": "spring", "style": "harmonic", "k": 2.0}], molecules=[chain], **keys
    )


def test_a_scene_s_chains_are_its_bonds_and_angles():
    # 60 particles, 12 chains of 5 on consecutive ids (docs/systems.md): bonds between
    # neighbours, angles at the inner beads with the middle one the vertex.
    sim = _melt(n=60, threads=1)
    sim.run(steps=20)
    assert sim.bond_types == ["spring"] and sim.angle_types == ["bend"]
    want_bonds = [[5 * c + k, 5 * c + k + 1] for c in range(12) for k in range(4)]
    want_angles = [[5 * c + k, 5 * c + k + 1, 5 * c + k + 2] for c in range(12) for k in range(3)]
    assert sim.bonds.tolist() == want_bonds and sim.bond_typeid.tolist() == [0] * 48
    assert sim.angles.tolist() == want_angles and sim.angle_typeid.tolist() == [0] * 36
    assert [c.tolist() for c in sim.chains] == [list(range(5 * c, 5 * c + 5)) for c in range(12)]


def test_a_data_file_s_bonds_are_read_by_atom_id(tmp_path):
    text = DATA.replace("2 atom types\n", "2 atom types\n2 bonds\n1 bond types\n")
    text = text.replace("Atoms # atomic", "Bond Coeffs # harmonic\n\n1 2 0\n\nAtoms # atomic")
    path = tmp_path / "bonded.data"
    path.write_text(text + "\nBonds\n\n1 1 4 3\n2 1 2 4\n")
    sim = dpd.Simulation(init=str(path), box=[4.0, 4.0, 4.0], density=4 / 64, threads=1)
    assert sim.bonds.tolist() == [[3, 2], [1, 3]] and sim.bond_types == ["1"]
    assert [c.tolist() for c in sim.chains] == [[1, 3, 2]]
    assert sim.angles.shape == (0, 3) and sim.angle_types == []


def _chain_sizes(q: np.ndarray, chains: list[np.ndarray], box: np.ndarray) -> tuple[float, float, float]:
    """Mean bond length, R_ee^2 and R_g^2 of the chains, unwrapped bond by bond."""
    lengths, ee, rg = [], [], []
    for c in chains:
        b = q[c[1:]] - q[c[:-1]]
        b -= box * np.round(b / box)
        lengths.extend(np.sqrt((b**2).sum(axis=1)))
        x = np.vstack([np.zeros(3), np.cumsum(b, axis=0)])
        ee.append(((x[-1] - x[0]) ** 2).sum())
        rg.append(((x - x.mean(axis=0)) ** 2).sum(axis=1).mean())
    return float(np.mean(lengths)), float(np.mean(ee)), float(np.mean(rg))


def test_chain_sizes_are_what_sampling_by_hand_gives():
    sim = _melt(n=150, seed=3, threads=1)
    sim.run(steps=40)
    snap = sim.snapshot()
    m = sim.measure(60, every=0.1, blocks=3)
    sim.restore(snap)
    sizes = []
    for _ in range(30):
        sim.run(steps=2)
        sizes.append(_chain_sizes(sim.positions, sim.chains, np.array(sim.box_lengths)))
    s = np.array(sizes)
    for k, e in enumerate((m.bond_length, m.end_to_end_squared, m.gyration_squared)):
        assert e is not None and e.mean == pytest.approx(s[:, k].mean(), rel=1e-12), k
        assert e.stderr == pytest.approx(_block_ratio_error(s[:, k], np.ones(30), 3), rel=1e-9), k


def test_ideal_chains_have_the_gaussian_sizes():
    # Without pair repulsion (a = 0) and angles, a chain of n beads on springs K r^2 is ideal:
    # each bond vector is Gaussian with variance 1 / 2K per component (k_B T = 1), so
    # <b^2> = 3 / 2K = 0.75, <|b|> = sqrt(8 / (2 pi K)) = 0.7979, <R_ee^2> = (n - 1) <b^2> = 3.0
    # and <R_g^2> = <b^2> (n^2 - 1) / 6n = 0.6 for n = 5. 40 chains, 150 time units sampled
    # every 0.5 in 10 blocks; BAOAB at dt = 0.02 (its configurational bias on the springs,
    # omega dt ~ 0.06, is far below the errors). Each mean is within four standard errors,
    # which are under 3 %: K r^2 / 2 (<R_ee^2> = 6) or n bonds in place of n - 1 (3.75) fail.
    sim = _melt(n=200, a=0.0, angle_types=None, scheme="baoab", dt=0.02, seed=11, threads=1)
    sim.run(steps=500)
    m = sim.measure(7500, every=0.5)
    for e, want in ((m.bond_length, np.sqrt(8 / (4 * np.pi))), (m.end_to_end_squared, 3.0),
                    (m.gyration_squared, 0.6)):
        assert e is not None and e.stderr is not None and e.stderr < 0.03 * want, (e, want)
        assert abs(e.mean - want) < 4 * e.stderr, (e, want)


def test_write_data_starts_the_same_system(tmp_path):
    # The file of sim.write_data (the writer of `dpd run --write-data`) read back as init: the
    # same types, masses, bonds, angles and positions bit for bit, velocities to rounding (the
    # file holds p / m), so the same potential energy and pressure. The file's particle count
    # and box are the simulation's (no `n`).
    sim = _melt(n=60, seed=2, threads=1)
    sim.run(steps=20)
    sim.write_data(tmp_path / "melt.data")
    back = dpd.Simulation(init=str(tmp_path / "melt.data"), threads=1)
    assert back.types == sim.types and np.array_equal(back.typeid, sim.typeid)
    assert np.array_equal(back.masses, sim.masses)
    assert np.array_equal(back.bonds, sim.bonds) and np.array_equal(back.angles, sim.angles)
    assert back.bond_types == ["1"] and back.angle_types == ["1"]
    assert np.array_equal(back.positions, sim.positions)
    assert np.allclose(back.velocities, sim.velocities, rtol=1e-14, atol=0)
    a, b = sim.observables(), back.observables()
    for name in ("potential_energy", "pressure"):
        assert b[name] == pytest.approx(a[name], rel=1e-12), name
    mix = _mixture(n=200, seed=3, threads=1)
    mix.write_data(tmp_path / "mix.data")
    again = _mixture(init=str(tmp_path / "mix.data"), threads=1)
    assert again.types == ["A", "B"] and np.array_equal(again.typeid, mix.typeid)
    assert np.array_equal(again.masses, mix.masses)
    with pytest.raises(ValueError, match=r"invalid write_data = \"x.data\": `dpd run` writes"):
        dpd.Simulation(write_data="x.data")  # type: ignore[call-arg]
    with pytest.raises(FileNotFoundError, match="missing"):
        sim.write_data(tmp_path / "missing" / "x.data")


def test_checkpoints_and_gsd_frames_keep_the_chains(tmp_path):
    # A checkpoint holds the topology: loaded into a simulation without bonds, it brings the
    # same bonds, angles and chains and continues bit for bit. A melt's GSD frame restarts it
    # with the scene's [[molecules]] (the frame's bonds must be theirs, docs/systems.md): the
    # same bonds, types and positions (GSD stores them in single precision).
    sim = _melt(n=60, seed=8, threads=1)
    sim.run(steps=10)
    sim.save_checkpoint(tmp_path / "melt.ckpt")
    other = dpd.Simulation(n=60, threads=1)
    other.load_checkpoint(tmp_path / "melt.ckpt")
    assert np.array_equal(other.bonds, sim.bonds) and np.array_equal(other.angles, sim.angles)
    assert [c.tolist() for c in other.chains] == [c.tolist() for c in sim.chains]
    sim.run(steps=10)
    other.run(steps=10)
    assert np.array_equal(other.positions, sim.positions)
    sim.trajectory(tmp_path / "melt.gsd", every=1.0)
    sim.trajectory(None)
    again = _melt(init=str(tmp_path / "melt.gsd"), threads=1)
    assert np.array_equal(again.bonds, sim.bonds) and np.array_equal(again.typeid, sim.typeid)
    assert np.allclose(again.positions, sim.positions, rtol=0, atol=1e-5)
