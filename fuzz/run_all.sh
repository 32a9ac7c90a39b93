#!/usr/bin/env bash
# Runs every fuzz target for RUNS executions (default 10^7) on one core, without a sanitizer
# (the targets are safe Rust: what matters is a panic, an abort, a timeout or memory past the
# limit, all of which libFuzzer reports), seeded from corpus/TARGET (made on first use from the
# regressions and the test data). Prints one summary line per target; a crash lands in
# artifacts/TARGET/ — copy it into regressions/TARGET/ once fixed. Needs nightly and cargo-fuzz.
set -euo pipefail
cd "$(dirname "$0")"
RUNS=${RUNS:-10000000}
for t in ${TARGETS:-image texture obj gltf cli_args height_sets}; do
    mkdir -p "corpus/$t" "artifacts/$t"
    cp -n regressions/"$t"/* "corpus/$t/" 2>/dev/null || true
    log="artifacts/$t.log"
    start=$(date +%s)
    status=0
    cargo +nightly fuzz run -O -s none "$t" "corpus/$t" -- \
        -runs="$RUNS" -rss_limit_mb=2048 -timeout=10 -artifact_prefix="artifacts/$t/" -print_final_stats=1 \
        > "$log" 2>&1 || status=$?
    secs=$(( $(date +%s) - start ))
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
    rss=$(grep -o 'stat::peak_rss_mb: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
    crashes=$(ls "artifacts/$t" | wc -l)
    echo "$t: $execs executions in ${secs}s, peak RSS ${rss} MB, exit $status, $crashes crash/timeout/oom files"
done
