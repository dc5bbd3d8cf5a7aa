#!/usr/bin/env bash
# The whole gate, as CI runs it: Rust format, lints and tests, then the
# Python package built from source, its tests, lints, types and stub.
#
#   bash scripts/gate.sh          the default gate (CI, .ci/run)
#   bash scripts/gate.sh --full   the default gate, then the full tier: the
#                                 long numerical matrices (#[ignore]d Rust
#                                 tests) in release; about two hours on
#                                 2 cores (docs/validation.md)
set -euo pipefail
cd "$(dirname "$0")/.."

full=0
case "${1:-}" in
    "") ;;
    --full) full=1 ;;
    *) echo "usage: bash scripts/gate.sh [--full]" >&2; exit 2 ;;
esac

echo "== cargo fmt"
cargo fmt --all -- --check

echo "== cargo clippy"
cargo clippy --workspace --all-targets -- -D warnings

echo "== cargo test"
# Default members: everything but the Python binding, which needs an
# interpreter to link and is tested through pytest below.
cargo test

echo "== pytest"
if command -v uv >/dev/null 2>&1; then
    uv=(uv)
else
    python3 -m pip install --quiet uv
    uv=(python3 -m uv)
fi
# uv builds the extension (release, via maturin) and installs the locked
# dependencies; --locked fails if uv.lock is out of date with pyproject.toml.
# Two workers (pytest-xdist), one per core of the CI machine; a module's
# tests stay on one worker so its fixtures are built once. The slowest tests
# are listed at the end.
"${uv[@]}" run --locked pytest -q -n 2 --dist loadscope --durations=15 tests/python

echo "== ruff, mypy, stubtest"
# Lints and types of the package and its tests (configured in
# pyproject.toml), and the binding's stub against the compiled module.
"${uv[@]}" run --locked ruff check python tests
"${uv[@]}" run --locked mypy
"${uv[@]}" run --locked python -m mypy.stubtest camlink._core

if [ "$full" = 1 ]; then
    echo "== full tier: the long matrices (release)"
    cargo test --release -- --ignored --nocapture
fi
