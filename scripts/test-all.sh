#!/usr/bin/env bash
# Every test the project has: formatting, lints, the Rust test suite, then each
# scripts/test-<topic>.sh (LAMMPS plugin, Python module, trajectory readers, ...), which install
# what they need into virtual environments under ${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo fmt --all -- --check
cargo clippy --workspace --all-targets --quiet -- -D warnings
cargo test --workspace
for script in scripts/test-*.sh; do
    [ "$script" = scripts/test-all.sh ] && continue
    echo "== $script"
    start=$SECONDS
    bash "$script"
    echo "== $script passed in $((SECONDS - start)) s"
done
