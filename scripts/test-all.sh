#!/usr/bin/env bash
# Every test the project has: formatting, lints, the Rust test suite, then each
# scripts/test-<topic>.sh (LAMMPS plugin, Python module, trajectory readers, ...), which install
# what they need into virtual environments under ${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}.
# Each phase prints its wall time (CI must stay under 20 minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
phase() {
    echo "== $*"
    local start=$SECONDS
    "$@"
    echo "== $* passed in $((SECONDS - start)) s"
}
# The scripts' virtual environments download while the Rust suite compiles (scripts/venvs.sh).
venvs_log=$(mktemp)
trap 'rm -f "$venvs_log"' EXIT
bash scripts/venvs.sh lammps python trajectory >"$venvs_log" 2>&1 &
venvs=$!
phase cargo fmt --all -- --check
# Clippy lints each crate of the workspace as the test build compiles it: cargo runs clippy's
# driver in place of rustc for the workspace's crates (RUSTC_WORKSPACE_WRAPPER with CLIPPY_ARGS,
# what `cargo clippy -- -D warnings` sets), so every crate is compiled once instead of being
# checked by `cargo clippy --all-targets` and then built again by `cargo test` (the separate
# clippy stage took 127-148 s of a clean run; net of the benchmarks' build below, about 70 s
# saved, measured side by side: docs/notes/2026-12-07-ci-time.md). It
# stays exported: the scripts' cargo builds below (the LAMMPS kernels, the Python module) reuse
# these artifacts only under the same wrapper, and maturin's build of dpd-python, which has no
# Rust test for `cargo test` to build, lints it there. The targets clippy checked that `cargo
# test` does not build are the benchmarks: built (so linted) first.
clippy_driver=$(command -v clippy-driver) ||
    { echo "clippy-driver not found: install clippy (rustup component add clippy)" >&2; exit 1; }
export RUSTC_WORKSPACE_WRAPPER=$clippy_driver
export CLIPPY_ARGS=-D__CLIPPY_HACKERY__warnings__CLIPPY_HACKERY__
phase cargo test --workspace --no-run --quiet --bench '*'
# One invocation for the unit, integration and doc tests: a separate `cargo test --doc` resolves
# another unit graph for the proc macros' host dependencies and rebuilt the workspace's
# dependency graph (measured in CI: 154 s, of which the doc tests themselves ~20 s), more than
# the examples this also builds cost (48 s of unit time at -j1, docs/notes/2026-12-07-ci-time.md).
phase cargo test --workspace
venvs_installed() {
    wait "$venvs" || { cat "$venvs_log"; return 1; }
}
phase venvs_installed
for script in scripts/test-*.sh; do
    [ "$script" = scripts/test-all.sh ] && continue
    phase bash "$script"
done
echo "== all passed in $SECONDS s"
