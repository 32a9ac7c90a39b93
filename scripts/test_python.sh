#!/usr/bin/env bash
# The Python package's tests, against the wheel as a user installs it: the wheel is built from
# this tree (maturin, release; one abi3 wheel for CPython 3.9 and later) with the build tools in
# their own environment, installed into a fresh virtual environment (target/python-test-venv)
# with nothing but its runtime dependency and the test tools (pytest; mypy for the stubs;
# dask.distributed for a
# batch through a LocalCluster; pypng and Pillow as
# independent PNG and APNG readers), and pytest runs there, comparing
# each function with the release `bumpmap` executable. Arguments go to pytest
# (e.g. `-k render -x`).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
PY=${PYTHON:-python3}
BUILD_VENV=$ROOT/target/python-build-venv
TEST_VENV=$ROOT/target/python-test-venv
WHEELS=$ROOT/target/python-wheel

cargo build --release -p bumpmap-cli
if [ ! -x "$BUILD_VENV/bin/maturin" ]; then
    "$PY" -m venv "$BUILD_VENV"
    "$BUILD_VENV/bin/pip" install --quiet --disable-pip-version-check "maturin>=1.7,<2"
fi
rm -rf "$WHEELS"
"$BUILD_VENV/bin/maturin" build --release --quiet -m python/Cargo.toml -i "$PY" --out "$WHEELS"

"$PY" -m venv --clear "$TEST_VENV"
"$TEST_VENV/bin/pip" install --quiet --disable-pip-version-check "$WHEELS"/bumpmap-*.whl pytest pypng pillow "dask[distributed]" mypy
# Run from outside the source tree, so `import bumpmap` can only find the installed wheel.
cd "$ROOT/target"
BUMPMAP_CLI="$ROOT/target/release/bumpmap" "$TEST_VENV/bin/python" -m pytest -q -p no:cacheprovider \
    --rootdir "$ROOT/python" "$ROOT/python/tests" "$@"
