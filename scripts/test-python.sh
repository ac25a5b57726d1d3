#!/usr/bin/env bash
# The Python module (python/, issues 27 and 48): builds the abi3 wheel with pip's source build
# (what `pip install ./python` runs), installs that wheel into a virtual environment under
# ${DPD_TEST_CACHE:-$HOME/.cache/dpd-test} (reused if present), and runs the pytest suite, the
# sessions of docs/python.md as doctests (their printed output is what the code prints) and mypy
# against the type stubs. The crate is a workspace member, formatted and linted with the rest by
# scripts/test-all.sh. maturin builds it with the settings of the `test` profile (optimised, as
# users' release builds are) so that it reuses what `cargo test --workspace` compiled instead of
# compiling every dependency again: `--profile test` itself would build a test harness, but `test`
# is `dev` with opt-level 3 and no debug information, and cargo identifies artifacts by their
# settings, not by the profile's name (and the features it resolves for -p dpd-python match the
# workspace's: workspace-hack/).
set -euo pipefail
cd "$(dirname "$0")/.."
cache="${DPD_TEST_CACHE:-$HOME/.cache/dpd-test}"
venv="$cache/python-venv"
# maturin, the build backend, is found on PATH.
export PATH="$venv/bin:$PATH"
bash scripts/venvs.sh python
wheels="$cache/wheels"
rm -rf "$wheels"
CARGO_PROFILE_DEV_OPT_LEVEL=3 CARGO_PROFILE_DEV_DEBUG=false MATURIN_PEP517_ARGS="--profile dev" "$venv/bin/pip" wheel --quiet \
    --no-build-isolation --no-deps --wheel-dir "$wheels" ./python
wheel=$(ls "$wheels"/dpd-*.whl)
# One wheel for every CPython >= 3.9 (the stable ABI), with the stubs and the PEP 561 marker.
case "$wheel" in *-cp39-abi3-*) ;; *) echo "not an abi3 wheel: $wheel"; exit 1 ;; esac
"$venv/bin/python" - "$wheel" <<'PY'
import sys, zipfile
names = set(zipfile.ZipFile(sys.argv[1]).namelist())
missing = {"dpd/__init__.pyi", "dpd/py.typed"} - names
assert not missing, f"the wheel lacks {missing}: {sorted(names)}"
PY
"$venv/bin/pip" install --quiet --force-reinstall --no-deps "$wheel"
# The stubs against the tests' use of the module, and a wrong type that mypy must catch: mypy
# (one thread, ~13 s) runs beside pytest.
stubs() {
    "$venv/bin/mypy" --cache-dir "$cache/mypy" --no-error-summary --check-untyped-defs python/tests
    if "$venv/bin/mypy" --cache-dir "$cache/mypy" --no-error-summary -c 'import dpd; dpd.Simulation(dt="0.05")' >/dev/null; then
        echo "mypy accepted dpd.Simulation(dt=\"0.05\"): the stubs type nothing"
        return 1
    fi
}
stubs &
mypy=$!
# pytest exits with 5 when it collects no test: a failure here like any other non-zero code.
"$venv/bin/pytest" -q python/tests docs/python.md --doctest-glob=python.md \
    -o doctest_optionflags="ELLIPSIS NORMALIZE_WHITESPACE"
wait "$mypy"
