#!/usr/bin/env bash
# Peak memory and time of the largest legal inputs (README "Memory", BENCHMARKS.md): each command
# under /usr/bin/time -v, without a limit and under a 4 GiB address-space limit (ulimit -v).
# Usage: scripts/measure_memory.sh [WORKDIR]   (default target/memory; needs python3, GNU time)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
work=${1:-$root/target/memory}
mkdir -p "$work"
cargo build --release -p bumpmap-cli --manifest-path "$root/Cargo.toml" >&2
B=$root/target/release/bumpmap
# 8-bit greyscale PNG height fields (a shifted ramp), written with zlib alone.
for n in 8192 16384; do
    [ -f "$work/h$n.png" ] || python3 - "$n" "$work/h$n.png" <<'PY'
import struct, sys, zlib
n, out = int(sys.argv[1]), sys.argv[2]
def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))
c = zlib.compressobj(1)
row = bytes((x * 7 + (x * x >> 9)) & 255 for x in range(n))
data = b''.join(c.compress(b'\0' + row[(y * 3) & 255:] + row[:(y * 3) & 255]) for y in range(n)) + c.flush()
with open(out, 'wb') as f:
    f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', n, n, 8, 0, 0, 0, 0))
            + chunk(b'IDAT', data) + chunk(b'IEND', b''))
PY
done
run() {
    local limit=$1 name=$2; shift 2
    rm -rf "$work/o_$name"; mkdir -p "$work/o_$name"
    local rc=0
    ( if [ "$limit" != none ]; then ulimit -v "$limit"; fi; cd "$work/o_$name" && /usr/bin/time -v "$B" "$@" ) \
        > "$work/$name.out" 2> "$work/$name.err" || rc=$?
    printf '| %s | %s | %s | %s | %s kB | %s\n' "$name" "$limit" "$rc" \
        "$(grep Elapsed "$work/$name.err" | sed 's/.*: //')" \
        "$(grep 'Maximum resident' "$work/$name.err" | sed 's/.*: //')" \
        "$(grep -E '^error|^wrote' "$work/$name.err" | head -1 | cut -c1-120)"
}
echo "| run | limit (KiB) | exit | time | peak | first line |"
H=$work
run none nm8 normalmap "$H/h16384.png" --mips -o n.png
run none nm16 normalmap "$H/h16384.png" --bits 16 --mips -o n.png
run none render16k render --height-field "$H/h16384.png" --size 512 -o r.png
run none render16k_sp render --height-field "$H/h16384.png" --technique single-pass --size 512 -o r.png
run none tess2048 render --tessellation 2048,2048 --size 512 -o t.png
run none spot render --technique single-pass --spot 0,0,-1 --spot-pattern pinwheel@16384 --size 64 -o s.png
run 4194304 nm8 normalmap "$H/h16384.png" --mips -o n.png
run 4194304 nm16 normalmap "$H/h16384.png" --bits 16 --mips -o n.png
run 4194304 render16k render --height-field "$H/h16384.png" --size 512 -o r.png
run 4194304 render8k render --height-field "$H/h8192.png" --size 512 -o r.png
run 4194304 emboss8k render --height-field "$H/h8192.png" --technique emboss --size 512 -o r.png
run 4194304 tess2048 render --tessellation 2048,2048 --size 512 -o t.png
