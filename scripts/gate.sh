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

if command -v uv >/dev/null 2>&1; then
    uv=(uv)
else
    python3 -m pip install --quiet uv
    uv=(python3 -m uv)
fi

# The three compilations run at once, each in its own target directory (so
# that none waits for another's lock): clippy's check build, the tests'
# build (dev profile: optimised dependencies), and the extension that uv
# builds through maturin (release) with the locked Python dependencies.
# Alone, each leaves a core idle in its serial stretches (the largest
# crates, the links); together they keep both cores busy. Their output
# goes to a log each, printed when the step fails.
logs=target/gate-logs
mkdir -p "$logs"
ext_target="$PWD/target/extension"
step() {  # step NAME COMMAND...: run in the background, output to its log
    local name=$1; shift
    ( rc=0; "$@" >"$logs/$name.log" 2>&1 || rc=$?; echo "$rc" >"$logs/$name.rc" ) &
}
rm -f "$logs"/*.rc
echo "== cargo clippy, cargo test --no-run, uv sync (maturin), at once"
step clippy env CARGO_TARGET_DIR="$PWD/target/clippy" \
    cargo clippy --workspace --all-targets -- -D warnings
# Default members: everything but the Python binding, which needs an
# interpreter to link and is tested through pytest below.
step build cargo test --no-run
# uv builds the extension (release, via maturin) and installs the locked
# dependencies; --locked fails if uv.lock is out of date with pyproject.toml.
step extension env CARGO_TARGET_DIR="$ext_target" "${uv[@]}" sync --locked
wait
failed=0
for name in clippy build extension; do
    rc=$(cat "$logs/$name.rc")
    if [ "$rc" != 0 ]; then
        echo "== $name failed (exit $rc):"
        cat "$logs/$name.log"
        failed=1
    else
        echo "   $name: $(grep -E 'Finished|Installed|Audited' "$logs/$name.log" | tail -n 1)"
    fi
done
[ "$failed" = 0 ] || exit 1

echo "== cargo test"
cargo test

echo "== pytest"
# Two workers (pytest-xdist), one per core of the CI machine; a module's
# tests stay on one worker so its fixtures are built once. The slowest tests
# are listed at the end. CARGO_TARGET_DIR keeps uv's check of the extension
# on the build above.
export CARGO_TARGET_DIR="$ext_target"
"${uv[@]}" run --locked pytest -q -n 2 --dist loadscope --durations=15 tests/python

echo "== ruff, mypy, stubtest"
# Lints and types of the package and its tests (configured in
# pyproject.toml), and the binding's stub against the compiled module.
"${uv[@]}" run --locked ruff check python tests
"${uv[@]}" run --locked mypy
"${uv[@]}" run --locked python -m mypy.stubtest camlink._core

if [ "$full" = 1 ]; then
    echo "== full tier: the long matrices (release)"
    env -u CARGO_TARGET_DIR cargo test --release -- --ignored --nocapture
fi
