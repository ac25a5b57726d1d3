#!/usr/bin/env bash
# The strongest substitute for a Miri run over dpd-core's unsafe code that CI can have (issue 24).
#
# Miri ships only as a rustup component of a nightly toolchain, from rustup's own distribution
# server; it is not on crates.io, PyPI or Debian, the registries CI reaches, so CI cannot
# install it. Instead, dpd-core's unit tests, which drive every unsafe path (the pair engine's
# two-particle writes and unchecked reads, the scalar and AVX2 lanes, the Philox batches, the
# binning's counting sort, on one thread and on several), run under valgrind's memcheck, which
# reports any read or write outside an allocation and any use of uninitialised memory. The test
# binary is the one `cargo test --workspace` built (the test profile keeps
# debug assertions, so the standard library's checks of `get_unchecked` and pointer arithmetic
# preconditions run too); nothing is rebuilt here.
set -euo pipefail
cd "$(dirname "$0")/.."

VALGRIND_VERSION=1:3.19.0-1
if ! command -v valgrind >/dev/null; then
    # Debian's package, pinned; the package lists are refreshed only if they lack it.
    apt-get install -y -qq "valgrind=$VALGRIND_VERSION" >/dev/null 2>&1 ||
        { apt-get update -qq && apt-get install -y -qq "valgrind=$VALGRIND_VERSION" >/dev/null; }
fi

# The unit-test executable of dpd-core's library, from cargo's build report.
bin=$(cargo test --workspace --no-run --message-format=json 2>/dev/null |
    grep '"name":"dpd_core"' | grep '"kind":\["lib"\]' | grep '"test":true' |
    sed -n 's/.*"executable":"\([^"]*\)".*/\1/p' | head -n 1)
if [ -z "$bin" ] || [ ! -x "$bin" ]; then
    echo "test-miri: no unit-test executable of dpd-core found" >&2
    exit 1
fi

# One test at a time: memcheck runs one thread at a time anyway, and the tests that compare
# thread counts build their own pools. Any memcheck error fails the run (exit code 99).
# Skipped: the Metropolis sampler's statistical test, 400 000 sweeps of two particles (7.7 s of
# the 45 under memcheck). metropolis.rs has no unsafe code, and its cell list is also driven by
# `energy_on_cells_equals_the_pair_sum`; the test still runs natively in `cargo test`.
valgrind --quiet --error-exitcode=99 --leak-check=no "$bin" --test-threads=1 \
    --skip metropolis::tests::two_particles_sample_the_boltzmann_density_of_their_distance
