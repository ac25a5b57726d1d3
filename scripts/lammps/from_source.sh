#!/usr/bin/env bash
# The plugin against a LAMMPS built from source with CMake, as on a cluster (issue 47; run by
# hand, not in CI: one LAMMPS build takes 15-30 min on 2 cores). Usage:
#
#   bash scripts/lammps/from_source.sh smallbig|bigbig
#
# Needs the virtual environment of scripts/test-lammps.sh (its cmake and MPICH; run that once)
# and the `dpd` binary of `cargo build -p dpd-cli` (or DPD=path). Steps, all under
# ${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}/lammps-source:
#  1. LAMMPS's source: Debian's tarball of the 4 Feb 2025 feature release (the registry this
#     project may reach; github.com is out of reach here), checked against its SHA-256;
#  2. LAMMPS configured with the given integer sizes, BUILD_SHARED_LIBS, PKG_PLUGIN, MOLECULE
#     and DPD-BASIC, MPI from the venv, built and installed to a prefix;
#  3. `dpd export lammps aboba vv`, the tree copied to a fresh directory and built there with
#     PATH holding no cargo or rustc, finding LAMMPS through its CMake package (`-DLAMMPS_DIR`),
#     which gives the headers, MPI's and the integer sizes;
#  4. scripts/lammps/check.py's equilibrium evidence for both schemes on 1 and 2 ranks with
#     that LAMMPS's `lmp` and this plugin, against `dpd run`.
set -euo pipefail
cd "$(dirname "$0")/../.."
sizes=${1:?give the integer sizes: smallbig or bigbig}
case $sizes in smallbig | bigbig) ;; *)
    echo "sizes = '$sizes': valid are smallbig and bigbig" >&2
    exit 2
    ;;
esac
cache=${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}
venv=$cache/lammps/venv
[ -x "$venv/bin/cmake" ] || {
    echo "$venv/bin/cmake not found: run bash scripts/test-lammps.sh once first" >&2
    exit 2
}
dpd=${DPD:-$PWD/target/debug/dpd}
[ -x "$dpd" ] || {
    echo "$dpd not found: cargo build -p dpd-cli, or set DPD" >&2
    exit 2
}
work=$cache/lammps-source
mkdir -p "$work"
tarball=lammps_20250204+dfsg.1.orig.tar.xz
sha=3671165bd52fad36734e0a9136c5bc5ecb225e03988f8c89aa13366a8b53b1c7
if ! echo "$sha  $work/$tarball" | sha256sum --check --status 2>/dev/null; then
    curl --fail --silent --show-error -o "$work/$tarball" \
        "http://deb.debian.org/debian/pool/main/l/lammps/$tarball"
    echo "$sha  $work/$tarball" | sha256sum --check --quiet
fi
src=$work/lammps-4Feb2025
[ -d "$src" ] || tar -xJf "$work/$tarball" -C "$work"
prefix=$work/prefix-$sizes
if [ ! -x "$prefix/bin/lmp" ]; then
    "$venv/bin/cmake" -S "$src/cmake" -B "$work/build-$sizes" -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_INSTALL_PREFIX="$prefix" -DBUILD_SHARED_LIBS=on -DLAMMPS_SIZES="$sizes" \
        -DPKG_PLUGIN=on -DPKG_MOLECULE=on -DPKG_DPD-BASIC=on -DBUILD_OMP=off \
        -DBUILD_MPI=on -DMPI_CXX_COMPILER="$venv/bin/mpicxx" -DMPI_C_COMPILER="$venv/bin/mpicc" \
        -DWITH_JPEG=off -DWITH_PNG=off -DWITH_FFMPEG=off -DWITH_GZIP=off >"$work/configure-$sizes.log"
    "$venv/bin/cmake" --build "$work/build-$sizes" -j2 >"$work/build-$sizes.log"
    "$venv/bin/cmake" --install "$work/build-$sizes" >/dev/null
fi
fresh=$(mktemp -d)
trap 'rm -rf "$fresh"' EXIT
"$dpd" export lammps aboba vv --out "$fresh/tree" >/dev/null
mkdir "$fresh/home"
env -i PATH="$venv/bin:/usr/bin:/bin" HOME="$fresh/home" sh -c '
    ! command -v cargo && ! command -v rustc &&
    cmake -S "$1/tree" -B "$1/build" -DLAMMPS_DIR="$2/lib/cmake/LAMMPS" | grep "^-- LAMMPS:" &&
    cmake --build "$1/build" >/dev/null' sh "$fresh" "$prefix"
# The installed lmp finds liblammps.so through LD_LIBRARY_PATH (LAMMPS installs no rpath).
printf '#!/bin/sh\nLD_LIBRARY_PATH=%s/lib exec %s/bin/lmp "$@"\n' "$prefix" "$prefix" >"$fresh/lmp"
chmod +x "$fresh/lmp"
"$venv/bin/python" scripts/lammps/check.py --lmp "$fresh/lmp" --mpirun "$venv/bin/mpirun" \
    --plugin "$fresh/build/dpdsplitplugin.so" --dpd "$dpd" --work "$work/runs-$sizes" \
    --only=equilibrium --scheme aboba --scheme vv --no-native
