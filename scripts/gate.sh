#!/usr/bin/env bash
# The whole gate, as CI runs it: Rust format, lints and tests, then the
# Python package built from source, its tests, lints, types and stub.
#
#   bash scripts/gate.sh          the default gate (CI, .ci/run)
#   bash scripts/gate.sh --full   the default gate, then the full tier: the
#                                 long numerical matrices (#[ignore]d Rust
#                                 tests), optimised (profile ci); figures
#                                 and time in docs/validation.md
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

# Two compilations run at once, each in its own target directory (so that
# neither waits for the other's lock): clippy's check build, and the one
# optimised build (profile `ci`, Cargo.toml) from which both the Rust tests
# and the Python extension come. The extension is built second, by uv
# through maturin with the same profile, so that it reuses every artifact
# of the tests' build and compiles only the binding and PyO3. Their output
# goes to a log each, printed when a step fails.
logs=target/gate-logs
mkdir -p "$logs"
# Every crate but the benchmarks (camlink-bench: divan) and the binding's
# test target (none: it is tested through pytest).
crates=(--workspace --exclude camlink-bench)
step() {  # step NAME COMMAND...: run in the background, output to its log
    local name=$1; shift
    ( rc=0; "$@" >"$logs/$name.log" 2>&1 || rc=$?; echo "$rc" >"$logs/$name.rc" ) &
}
build() {  # the tests' build, then the extension from its artifacts
    cargo test --profile ci "${crates[@]}" --no-run || return
    # uv installs the locked dependencies and builds the extension (maturin;
    # --locked fails if uv.lock is out of date with pyproject.toml).
    MATURIN_PEP517_ARGS="--profile ci" "${uv[@]}" sync --locked
}
rm -f "$logs"/*.rc
echo "== cargo clippy; cargo test --no-run then uv sync (maturin), at once"
step clippy env CARGO_TARGET_DIR="$PWD/target/clippy" \
    cargo clippy --workspace --all-targets -- -D warnings
step build build
wait
failed=0
for name in clippy build; do
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
cargo test --profile ci "${crates[@]}"

echo "== pytest"
# Two workers (pytest-xdist), one per core of the CI machine; a module's
# tests stay on one worker so its fixtures are built once. The slowest tests
# are listed at the end. --no-sync: the environment is the one synced above
# (a sync here could rebuild the extension in release).
"${uv[@]}" run --no-sync pytest -q -n 2 --dist loadscope --durations=15 tests/python

echo "== ruff, mypy, stubtest"
# Lints and types of the package and its tests (configured in
# pyproject.toml), and the binding's stub against the compiled module.
"${uv[@]}" run --no-sync ruff check python tests
"${uv[@]}" run --no-sync mypy
"${uv[@]}" run --no-sync python -m mypy.stubtest camlink._core

if [ "$full" = 1 ]; then
    echo "== full tier: the long matrices (profile ci, the build above)"
    cargo test --profile ci "${crates[@]}" -- --ignored --nocapture
fi
