#!/usr/bin/env python3
"""What a kept `Renderer` costs per frame from Python against `bumpmap bench render`, the same
frames in Rust: 20 frames of the torus with the first light orbiting the point looked at (the
peer's orbit, `(4 cos a, 4 sin a, 3)`), 512², per technique and backend. Python's frames are
read back into a NumPy array each (`bench render` reads none back); the scene is prepared once,
untimed, as `bench render`'s is. Medians of 5 runs of 20 frames, interleaved with the CLI's.

Run with the Python that has the wheel installed (scripts/test_python.sh makes one):
    target/python-test-venv/bin/python python/bench/kept_renderer.py [--backends cpu gpu]
Prints a Markdown table, then one JSON line."""

import argparse
import json
import math
import os
import statistics
import subprocess
import time
from pathlib import Path

import bumpmap

REPO = Path(__file__).resolve().parents[2]
CLI = Path(os.environ.get("BUMPMAP_CLI", REPO / "target" / "release" / "bumpmap"))


def python_ms(renderer, technique, size, frames, runs):
    scene = renderer.prepare(technique=technique, size=size)
    # The torus's default light, (4 cos a, 4 sin a, 3) from a = -2.2 round the circle.
    lights = [(4 * math.cos(-2.2 + 2 * math.pi * k / frames), 4 * math.sin(-2.2 + 2 * math.pi * k / frames), 3)
              for k in range(frames)]
    scene.render(light=lights[0])
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        for light in lights:
            scene.render(light=light)
        times.append((time.perf_counter() - start) * 1e3 / frames)
    return statistics.median(times)


def cli_ms(backend, technique, size, frames, runs):
    out = subprocess.run([str(CLI), "bench", "render", "--backend", backend, "--technique", technique, "--size",
                          str(size), "--frames", str(frames), "--runs", str(runs), "--json"],
                         capture_output=True, text=True, check=True).stdout
    return json.loads(out.strip().splitlines()[-1])["ms_per_frame"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--backends", nargs="+", default=["cpu", "gpu"])
    parser.add_argument("--techniques", nargs="+", default=["kilgard", "single-pass"])
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--frames", type=int, default=20)
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    rows = []
    print("| backend | technique | Python, kept Renderer (ms/frame) | bench render (ms/frame) | ratio |")
    print("| --- | --- | --- | --- | --- |")
    for backend in args.backends:
        try:
            renderer = bumpmap.Renderer(backend)
        except RuntimeError as e:
            print(f"| {backend} | | (no {backend}: {e}) | | |")
            continue
        for technique in args.techniques:
            py = python_ms(renderer, technique, args.size, args.frames, args.runs)
            cli = cli_ms(backend, technique, args.size, args.frames, args.runs)
            rows.append({"backend": backend, "technique": technique, "python_ms": py, "cli_ms": cli, "ratio": py / cli})
            print(f"| {backend} | {technique} | {py:.2f} | {cli:.2f} | {py / cli:.2f}× |")
    print(json.dumps({"bench": "kept_renderer", "size": args.size, "frames": args.frames, "rows": rows}))


if __name__ == "__main__":
    main()
