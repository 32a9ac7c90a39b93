#!/usr/bin/env bash
# The Python package's tests, against the wheel as it is published: scripts/build_wheel.sh builds
# it from this tree (one abi3 manylinux2014 wheel for CPython 3.9 and later, its native module
# built for baseline x86-64 and for x86-64-v3), it is installed into a fresh virtual environment
# (target/python-test-venv) with nothing but its runtime dependency and the test tools (pytest;
# mypy for the stubs; dask.distributed for a batch through a LocalCluster; pypng and Pillow as
# independent PNG and APNG readers; auditwheel to read the wheel's platform tag; bpy, Blender 5.0
# as a module, where this Python has its wheel), and pytest runs there, comparing each function
# with the release `bumpmap` executable. Arguments go to pytest (e.g. `-k render -x`).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
PY=${PYTHON:-python3}
TEST_VENV=$ROOT/target/python-test-venv
WHEELS=$ROOT/target/python-wheel

cargo build --release -p bumpmap-cli
scripts/build_wheel.sh

"$PY" -m venv --clear "$TEST_VENV"
"$TEST_VENV/bin/pip" install --quiet --disable-pip-version-check "$WHEELS"/bumpmap-*.whl pytest pypng pillow "dask[distributed]" mypy auditwheel
# Blender 5.0's bpy has wheels for CPython 3.11 only; test_blender_example.py skips elsewhere.
if "$TEST_VENV/bin/python" -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))'; then
    "$TEST_VENV/bin/pip" install --quiet --disable-pip-version-check "bpy>=5.0,<5.1"
fi
# Run from outside the source tree, so `import bumpmap` can only find the installed wheel.
cd "$ROOT/target"
BUMPMAP_WHEEL=$(echo "$WHEELS"/bumpmap-*.whl) BUMPMAP_CLI="$ROOT/target/release/bumpmap" "$TEST_VENV/bin/python" -m pytest -q -p no:cacheprovider \
    --rootdir "$ROOT/python" "$ROOT/python/tests" "$@"
