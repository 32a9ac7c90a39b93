#!/usr/bin/env bash
# The web page: `scripts/web.sh build` makes it into target/web/ (static files: index.html,
# app.js, worker.js, style.css and the module bumpmap_web.wasm, which any static server serves);
# `scripts/web.sh serve [PORT]` builds it and serves it at http://localhost:PORT/ (8000).
# Needs the wasm32-unknown-unknown target (rustup target add wasm32-unknown-unknown).
set -euo pipefail
cd "$(dirname "$0")/.."
out=target/web

build() {
    if command -v rustup >/dev/null && ! rustup target list --installed | grep -q wasm32-unknown-unknown; then
        rustup target add wasm32-unknown-unknown
    fi
    cargo build --profile web --target wasm32-unknown-unknown -p bumpmap-web
    mkdir -p "$out"
    cp web/index.html web/app.js web/worker.js web/style.css "$out/"
    cp target/wasm32-unknown-unknown/web/bumpmap_web.wasm "$out/"
    echo "built $out/ ($(du -k "$out/bumpmap_web.wasm" | cut -f1) KiB of wasm)"
}

case "${1:-build}" in
    build) build ;;
    serve)
        build
        port="${2:-8000}"
        echo "serving http://localhost:$port/ (Ctrl-C to stop)"
        exec python3 -m http.server --directory "$out" "$port"
        ;;
    *) echo "usage: scripts/web.sh build | serve [PORT]" >&2; exit 2 ;;
esac
