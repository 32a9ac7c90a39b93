#!/usr/bin/env python3
"""How much the Python boundary costs: `bumpmap.mip_chain` on a 4096x4096 uint8 array from
Python (arrays in and out included) against `bumpmap bench normalmap` (the same work in Rust,
no boundary), in interleaved rounds, and against the NumPy peer when its folder is given.

Run with the Python that has the wheel installed (scripts/test_python.sh makes one):
    target/python-test-venv/bin/python python/bench/normal_map_speed.py [--peers ../shared/peers]
Prints one JSON line last."""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import bumpmap

REPO = Path(__file__).resolve().parents[2]


def bench_heights(size):
    """The heights `bumpmap bench normalmap` times: bricks·247 + noise·8, clamped, in float32."""
    bricks = bumpmap.read_height_field(f"bricks@{size}").astype(np.float32)
    noise = bumpmap.read_height_field(f"noise:7@{size}").astype(np.float32)
    mixed = bricks * np.float32(247.0) + noise * np.float32(8.0)
    return np.clip(mixed, 0, 255).astype(np.uint8)


def time_python(heights, runs):
    bumpmap.mip_chain(heights)  # warm-up
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        bumpmap.mip_chain(heights)
        times.append((time.perf_counter() - t) * 1e3)
    return statistics.median(times)


def time_cli(cli, size, runs):
    out = subprocess.run([cli, "bench", "normalmap", "--size", str(size), "--runs", str(runs), "--json"],
                         capture_output=True, text=True, check=True).stdout
    return json.loads(out.strip().splitlines()[-1])["median_ms"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--size", type=int, default=4096)
    ap.add_argument("--runs", type=int, default=9)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--cli", default=os.environ.get("BUMPMAP_CLI", str(REPO / "target" / "release" / "bumpmap")))
    ap.add_argument("--peers", help="../shared/peers: also time its NumPy normal map")
    args = ap.parse_args()
    heights = bench_heights(args.size)
    rounds = []
    for r in range(args.rounds):
        py = time_python(heights, args.runs)
        rust = time_cli(args.cli, args.size, args.runs)
        rounds.append({"python_ms": py, "cli_ms": rust, "ratio": py / rust})
        print(f"round {r + 1}: bumpmap.mip_chain {py:.1f} ms, bumpmap bench normalmap {rust:.1f} ms -> {py / rust:.3f}x",
              file=sys.stderr)
    result = {"size": args.size, "runs": args.runs, "rounds": rounds,
              "median_ratio": statistics.median(r["ratio"] for r in rounds),
              "python_median_ms": statistics.median(r["python_ms"] for r in rounds)}
    if args.peers:
        peer = subprocess.run([sys.executable, str(Path(args.peers) / "numpy_normalmap.py"), "--size", str(args.size),
                               "--runs", "5"], capture_output=True, text=True, check=True).stdout
        numpy_ms = json.loads(peer.strip().splitlines()[-1])["s_median"] * 1e3
        result["numpy_peer_ms"] = numpy_ms
        result["numpy_over_python"] = numpy_ms / result["python_median_ms"]
        print(f"NumPy peer {numpy_ms:.0f} ms -> bumpmap from Python is {numpy_ms / result['python_median_ms']:.1f}x faster",
              file=sys.stderr)
    print(json.dumps(result))


if __name__ == "__main__":
    main()
