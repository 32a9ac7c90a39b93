#!/usr/bin/env bash
# The viewer's frame rates and the time from `+` to the first frame with the new bumps
# (BENCHMARKS.md), in one run: `bumpmap view` scripted under a virtual X server. Each frame
# rate is over 150 frames after the first, the light orbiting, drawn and shown in an 800x600
# window; the rebuild times are each key's time to the next frame with a 1024² height field.
# Usage: scripts/bench_viewer.sh [scaling]   (needs xvfb-run; the GPU rows need an adapter: lavapipe)
# With `scaling`, only the CPU frame rates of `kilgard` and `single-pass` at 800x600 and
# 1920x1080, each with 1 and 2 worker threads (RAYON_NUM_THREADS), so the scaling is seen.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# From the repository's root: cargo reads .cargo/config.toml (the x86-64-v3 target) from the
# working directory, not from the manifest's, and a build from elsewhere is 4× slower.
cd "$root"
cargo build --release -p bumpmap-cli >&2
B=$root/target/release/bumpmap
x() { xvfb-run -a -s "-screen 0 1024x768x24" "$B" view --width 800 --height 600 "$@" 2>&1; }
if [ "${1:-}" = scaling ]; then
    for size in 800x600 1920x1080; do
        for technique in kilgard single-pass; do
            for threads in 1 2; do
                printf '%s %s %s threads: ' "$size" "$technique" "$threads"
                RAYON_NUM_THREADS=$threads xvfb-run -a -s "-screen 0 1920x1080x24" "$B" view --width "${size%x*}" \
                    --height "${size#*x}" --backend cpu --technique "$technique" --frames 151 2>&1 | grep "frames/s"
            done
        done
    done
    exit 0
fi
for backend in cpu gpu; do
    for technique in kilgard single-pass horizon pom height-exact; do
        x --backend "$backend" --technique "$technique" --frames 151 | grep "frames/s"
    done
done
keys=plus,minus,plus,minus,plus,minus,plus,minus,plus,minus
for technique in kilgard single-pass; do
    echo "+/- with noise:7@1024 ($technique, cpu): ms to the next frame, each key"
    x --backend cpu --technique "$technique" --height-field noise:7@1024 --keys "$keys" | grep "the next frame" \
        | sed 's/.*after \([0-9.]*\) ms/\1/' | sort -n | tr '\n' ' '
    echo
done
