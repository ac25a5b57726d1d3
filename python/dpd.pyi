"""Type stubs of the module `dpd` (python/src): what mypy and IDEs see.

Every scene keyword is optional (absent: the scene file's value, else the default of
docs/cli.md); tables take a dict of their keys.
"""

import os
from typing import Any, Literal, Mapping, Sequence, TypedDict, Union

import numpy as np
import numpy.typing as npt
from typing_extensions import Unpack

__version__: str

_Path = Union[str, "os.PathLike[str]"]
_Table = Mapping[str, Any]
_Field = Literal["velocity", "mass", "image", "observables"]

class SceneKeys(TypedDict, total=False):
    """The scene keys a keyword may set (docs/cli.md)."""

    description: str
    scheme: str
    n: int
    density: float
    box: Sequence[float]
    a: float
    gamma: float
    kbt: float
    mass: float
    weight_exponent: float
    dt: float
    time: float
    average_fraction: float
    sample_interval: float
    seed: int
    runs: int
    threads: int
    skin: float
    shear_rate: float
    body_force: float
    walls: _Table
    rdf: _Table
    vacf: _Table
    profile: _Table
    sweep: _Table
    trajectory: _Table
    init: str
    init_reset: bool
    energy_balance: bool
    like_neighbours: bool
    species: Sequence[_Table]
    pairs: _Table
    bond_types: Sequence[_Table]
    angle_types: Sequence[_Table]
    molecules: Sequence[_Table]

class BlowUpError(RuntimeError):
    """A step produced a non-finite value or moved a particle too far."""

def check(scheme: str) -> dict[str, Any]:
    """The order analysis of a registry name or a scheme string (`dpd check --json`)."""

def schemes() -> list[dict[str, Any]]:
    """The registry of named schemes (`dpd schemes --json`)."""

def sweep(
    *,
    schemes: Union[str, Sequence[str], None] = None,
    dt_min: float | None = None,
    dt_max: float | None = None,
    dt_factor: float | None = None,
    reference: str | None = None,
    observable: Literal["configurational-temperature", "viscosity"] | None = None,
    json: _Path | None = None,
    fresh: bool = False,
    scene: _Path | None = None,
    **keys: Unpack[SceneKeys],
) -> dict[str, Any]:
    """Schemes over a geometric range of dt, as `dpd sweep`: the results file's content."""

def kl(
    scheme: str,
    /,
    *,
    samples: int | None = None,
    protocol_time: float | None = None,
    sweeps_between: int | None = None,
    scene: _Path | None = None,
    **keys: Unpack[SceneKeys],
) -> dict[str, Any]:
    """The KL divergence of a scheme's configurations from exp(-U / k_B T) (`dpd kl --json`)."""

class Snapshot:
    """A copy of a simulation's state; `Simulation.restore` continues from it bit for bit."""

    @property
    def step(self) -> int: ...

class Estimate:
    """A mean over a run's samples and its standard error from block averages."""

    @property
    def mean(self) -> float: ...
    @property
    def stderr(self) -> float | None:
        """None with fewer samples than blocks."""

class Measurement:
    """What `Simulation.measure` measured, in reduced units."""

    @property
    def samples(self) -> int: ...
    @property
    def interval(self) -> float:
        """Time between samples."""

    @property
    def blocks(self) -> int: ...
    @property
    def kinetic_temperature(self) -> Estimate: ...
    @property
    def configurational_temperature(self) -> Estimate: ...
    @property
    def potential_energy(self) -> Estimate: ...
    @property
    def pressure(self) -> Estimate: ...
    @property
    def rdf(self) -> npt.NDArray[np.float64] | None:
        """Rows (r, g(r)), one per bin."""

    @property
    def vacf(self) -> npt.NDArray[np.float64] | None:
        """Rows (t, C(t)), t from 0 in steps of `interval`."""

    @property
    def diffusion(self) -> float | None: ...
    @property
    def pair_rdf(self) -> dict[str, npt.NDArray[np.float64]] | None:
        """With `rdf` and several types: rows (r, g_ij(r)) per pair of types, keyed "A-B"."""

    @property
    def like_neighbours(self) -> dict[str, Estimate | None] | None:
        """Per type, the fraction of its neighbours within r_c of the same type."""

    @property
    def species_profile(self) -> dict[str, npt.NDArray[np.float64]] | None:
        """Per type, rows (slab centre, number density)."""

    @property
    def bond_length(self) -> Estimate | None: ...
    @property
    def end_to_end_squared(self) -> Estimate | None: ...
    @property
    def gyration_squared(self) -> Estimate | None: ...

class Simulation:
    """One scene's system stepped by one scheme."""

    def __init__(
        self,
        *,
        allow_inconsistent: bool = False,
        scene: _Path | None = None,
        **keys: Unpack[SceneKeys],
    ) -> None: ...
    def run(self, steps: int) -> None:
        """Advance `steps` steps of dt (the GIL released; Ctrl-C stops it)."""

    def measure(
        self,
        steps: int,
        *,
        every: float | None = None,
        blocks: int = 10,
        rdf: bool | _Table | None = None,
        vacf: bool | _Table | None = None,
        profile: bool | _Table | None = None,
        like_neighbours: bool | None = None,
        accumulate: bool = False,
    ) -> Measurement:
        """Run `steps` steps sampling every `every` time units: means with standard errors,
        g(r), the velocity autocorrelation, per-type and chain observables; with
        `accumulate`, over the previous call's samples too."""

    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """(N, 3) positions in the box, row i for particle i."""

    @positions.setter
    def positions(self, value: npt.ArrayLike) -> None: ...
    @property
    def velocities(self) -> npt.NDArray[np.float64]:
        """(N, 3) velocities p / m, row i for particle i."""

    @velocities.setter
    def velocities(self, value: npt.ArrayLike) -> None: ...
    @property
    def typeid(self) -> npt.NDArray[np.int64]:
        """(N,) type of each particle, an index into `types`."""

    @property
    def types(self) -> list[str]:
        """Names of the particle types (the species, else A, B, ...)."""

    @property
    def masses(self) -> npt.NDArray[np.float64]:
        """(N,) mass of each particle."""

    @property
    def bonds(self) -> npt.NDArray[np.int64]:
        """(B, 2) particle ids of each bond."""

    @property
    def bond_typeid(self) -> npt.NDArray[np.int64]: ...
    @property
    def bond_types(self) -> list[str]: ...
    @property
    def angles(self) -> npt.NDArray[np.int64]:
        """(A, 3) particle ids (i, j, k) of each angle, j the vertex."""

    @property
    def angle_typeid(self) -> npt.NDArray[np.int64]: ...
    @property
    def angle_types(self) -> list[str]: ...
    @property
    def chains(self) -> list[npt.NDArray[np.int64]]:
        """Particle ids along each linear chain of bonds."""

    @property
    def step(self) -> int: ...
    @property
    def time(self) -> float: ...
    @property
    def dt(self) -> float: ...
    @dt.setter
    def dt(self, value: float) -> None: ...
    @property
    def scheme(self) -> str: ...
    @scheme.setter
    def scheme(self, value: str) -> None: ...
    @property
    def box_lengths(self) -> list[float]: ...
    @property
    def scene(self) -> dict[str, Any]: ...
    def observables(self) -> dict[str, float]:
        """The instantaneous observables of the current state."""

    def snapshot(self) -> Snapshot: ...
    def restore(self, snapshot: Snapshot) -> None: ...
    def save_checkpoint(self, path: _Path) -> None: ...
    def load_checkpoint(self, path: _Path) -> None: ...
    def write_data(self, path: _Path) -> None:
        """Write the state as a LAMMPS data file (with the bonds and angles)."""

    def trajectory(
        self,
        file: _Path | None,
        every: float | None = None,
        fields: Sequence[_Field] | None = None,
    ) -> None:
        """Write frames to `file` now and every `every` time units of the following runs."""
