#!/usr/bin/env bash
# A glTF scene's per-part cost (BENCHMARKS.md, #37): the same 100 tiles (51,200 triangles) drawn
# as 100 primitives with 20 materials (parts100.gltf), and as one primitive with one material
# (parts1.gltf, the floor), by `bench render` with the light orbiting, on the CPU and the GPU
# (lavapipe here), for the three-pass and the single-pass technique. The ratio is what the
# parts cost beyond their triangles: per part, a vertex stage and a draw per technique pass.
# Usage: scripts/bench_parts.sh [SIZE] [FRAMES]   (defaults 512 and 30; the GPU rows need an adapter)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# From the repository's root: cargo reads .cargo/config.toml (the x86-64-v3 target) from there.
cd "$root"
cargo build --release -p bumpmap-cli >&2
B=$root/target/release/bumpmap
size=${1:-512}
frames=${2:-30}
dir=$root/target/bench-parts
python3 scripts/make_parts_scene.py "$dir" >&2
ms() {
    "$B" bench render --scene "mesh:$dir/$1.gltf" --backend "$2" --technique "$3" --size "$size" \
        --frames "$frames" --runs 5 --json 2>/dev/null | sed -E 's/.*"ms_per_frame":([0-9.]+).*/\1/'
}
printf '| backend | technique | 100 parts, 20 materials (ms/frame) | 1 part (ms/frame) | ratio |\n| --- | --- | --- | --- | --- |\n'
for backend in cpu gpu; do
    for technique in kilgard single-pass; do
        parts=$(ms parts100 "$backend" "$technique") || { echo "| $backend | $technique | (no $backend) | | |"; continue; }
        one=$(ms parts1 "$backend" "$technique")
        printf '| %s | %s | %s | %s | %.2f× |\n' "$backend" "$technique" "$parts" "$one" "$(echo "$parts / $one" | bc -l)"
    done
done
