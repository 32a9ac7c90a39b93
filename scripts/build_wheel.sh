#!/usr/bin/env bash
# Builds the Python wheel as it is published, into target/python-wheel/: one abi3 wheel for
# CPython 3.9 and later on x86-64 Linux with glibc 2.17 or later (manylinux2014), linked by zig
# against glibc 2.17's symbols (maturin --zig). It holds the native module twice: built for
# baseline x86-64, which runs on every x86-64 processor, and for x86-64-v3 (AVX2, FMA, BMI2),
# where the CPU pipeline is four to five times faster; `import bumpmap` loads the second where
# the processor has what it needs (python/bumpmap/_native.py). Elsewhere than x86-64 Linux it
# builds the one module for this machine. The build tools live in target/python-build-venv.
#
# Usage: scripts/build_wheel.sh    (then: pip install target/python-wheel/bumpmap-*.whl)
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
PY=${PYTHON:-python3}
BUILD_VENV=$ROOT/target/python-build-venv
WHEELS=$ROOT/target/python-wheel

if ! "$BUILD_VENV/bin/python" -c 'import maturin, ziglang, wheel' >/dev/null 2>&1; then
    "$PY" -m venv "$BUILD_VENV"
    "$BUILD_VENV/bin/pip" install --quiet --disable-pip-version-check "maturin>=1.7,<2" "ziglang>=0.13" "wheel>=0.42"
fi
# maturin finds zig as `python -m ziglang` of the first python on PATH.
export PATH="$BUILD_VENV/bin:$PATH"
rm -rf "$WHEELS"

if [ "$(uname -s)-$(uname -m)" != Linux-x86_64 ]; then
    maturin build --release --quiet -m python/Cargo.toml -i "$PY" --out "$WHEELS"
    exit 0
fi

STAGE=$ROOT/target/python-wheel-stage
rm -rf "$STAGE"
# LEVEL → a manylinux2014 wheel whose module is built for that x86-64 level, in $STAGE/LEVEL.
# No debug line tables: the module is stripped anyway, and they cost build time.
build() {
    echo "building the native module for $1 (manylinux2014, zig)" >&2
    CARGO_PROFILE_RELEASE_DEBUG=false RUSTFLAGS="-C target-cpu=$1" maturin build --release --strip --quiet --zig --compatibility manylinux2014 \
        -m python/Cargo.toml -i "$PY" --target-dir "target/wheel-$1" --out "$STAGE/$1"
    # CI builds once on a disk that has run out (lld's Bus error, 2026-12-08): its build folder
    # (about 770 MB) goes once the wheel is out of it. Here it stays, for the next build.
    if [ -n "${CI:-}" ]; then rm -rf "target/wheel-$1"; fi
}
build x86-64-v3
build x86-64

# The baseline wheel with the x86-64-v3 module added beside its own; `wheel pack` writes the
# RECORD (every file's hash) again.
"$BUILD_VENV/bin/python" -m wheel unpack --dest "$STAGE/unpacked" "$STAGE"/x86-64/bumpmap-*.whl
(cd "$STAGE/x86-64-v3" && "$BUILD_VENV/bin/python" -m zipfile -e bumpmap-*.whl fast)
unpacked=$(echo "$STAGE"/unpacked/bumpmap-*)
for so in "$STAGE"/x86-64-v3/fast/bumpmap/_bumpmap.*so; do
    cp "$so" "$unpacked/bumpmap/_bumpmap_x86_64_v3.${so##*/_bumpmap.}"
done
mkdir -p "$WHEELS"
"$BUILD_VENV/bin/python" -m wheel pack --dest-dir "$WHEELS" "$unpacked"
ls "$WHEELS"
