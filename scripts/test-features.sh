#!/usr/bin/env bash
# The Python module (maturin: `-p dpd-python`) and the LAMMPS kernels (the plugin's CMake:
# `-p dpd-lammps`) are built apart from the workspace; they reuse what `cargo test --workspace`
# compiled only if cargo resolves the same features for every shared dependency
# (workspace-hack/Cargo.toml says why). Fails naming each dependency whose features differ.
set -euo pipefail
cd "$(dirname "$0")/.."
# One line per package and feature set: host and target builds of a package appear apart.
features() {
    cargo tree --quiet --locked "$@" -f '{p} [{f}]' --prefix none --no-dedupe \
        | sed 's/ (\*)$//; s/ (proc-macro)//' | grep -v '^workspace-hack ' | sort -u
}
workspace=$(features --workspace -e normal,build,dev)
status=0
for package in dpd-python dpd-lammps; do
    differ=$(comm -13 <(echo "$workspace") <(features -p "$package" -e normal,build))
    if [ -n "$differ" ]; then
        echo "cargo build -p $package resolves other features than the workspace build for:"
        echo "$differ" | sed 's/^/    /'
        echo "  (the workspace build has: $(for p in $(echo "$differ" | cut -d' ' -f1 | sort -u); do
            echo "$workspace" | grep "^$p v"; done | tr '\n' ';'))"
        echo "  add the missing features to workspace-hack/Cargo.toml"
        status=1
    fi
done
exit $status
