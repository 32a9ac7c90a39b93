#!/usr/bin/env bash
# Runs every peer in ../shared/peers and the matching `bumpmap bench` back to back, in one run,
# and prints the ratios that BENCHMARKS.md quotes. Install the peers first (`sh setup.sh` in the
# peers folder, as root). Usage: scripts/compare_peers.sh [PEERS_DIR] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
PEERS=${1:-../shared/peers}
OUT=${2:-target/peers}
mkdir -p "$OUT"
# The peers write into their own out/ folder; work on a copy so the shared one stays read-only.
work=$(mktemp -d)
cp -r "$PEERS"/. "$work"
chmod -R u+w "$work"
cargo build --release --quiet
B=target/release/bumpmap
quiet() { python3 "$work/cpuload.py" 0.15 300 || echo "warning: other processes are busy; figures will be noisy"; }

echo "== normal map: 4096² 8-bit heights -> normal map + 13 mips" >&2
quiet; python3 "$work/numpy_normalmap.py" --size 4096 --runs 5 | tail -n 1 > "$OUT/numpy_normalmap.json"
quiet; $B bench normalmap --size 4096 --runs 9 --json > "$OUT/bumpmap_normalmap.json"
quiet; $B bench normalmap --size 4096 --runs 9 --threads 1 --json > "$OUT/bumpmap_normalmap_t1.json"

# The Python package (scripts/test_python.sh installs it into target/python-test-venv): the same
# work called from Python, arrays in and out, against `bench normalmap` in alternating rounds.
if [ -x target/python-test-venv/bin/python ]; then
  quiet; target/python-test-venv/bin/python python/bench/normal_map_speed.py --size 4096 --runs 9 --rounds 3 \
    --cli "$B" | tail -n 1 > "$OUT/python_normalmap.json"
fi

echo "== tangents: 1,000,000-triangle grid" >&2
src=$(ls -d "$work"/out/pymikktspace-0.3.0/_external/MikkTSpace 2>/dev/null || true)
if [ -z "$src" ]; then
  # setup.sh keeps the C sources in the peers' out/; fetch them again where that copy is gone.
  # (Cython < 3, as setup.sh: pip prepares the sdist's metadata, which fails under Cython 3.)
  echo 'cython<3' > "$work/out/cython-constraint.txt"
  PIP_CONSTRAINT="$work/out/cython-constraint.txt" pip download --quiet --no-deps -d "$work/out" pymikktspace==0.3.0 >&2 &&
    tar xzf "$work/out/pymikktspace-0.3.0.tar.gz" -C "$work/out" &&
    src=$(ls -d "$work"/out/pymikktspace-0.3.0/_external/MikkTSpace 2>/dev/null || true)
  [ -n "$src" ] || echo "warning: no MikkTSpace C sources; the C column will be missing" >&2
fi
quiet; python3 "$work/mikktspace_bench.py" --tris 1000000 --runs 1 --c-runs 5 ${src:+--c-src "$src"} | tail -n 1 > "$OUT/mikktspace.json"
quiet; $B bench tangents --triangles 1000000 --runs 5 --json > "$OUT/bumpmap_tangents_ours.json"
quiet; $B bench tangents --triangles 1000000 --runs 3 --mode mikktspace --json > "$OUT/bumpmap_tangents_mikktspace.json"
quiet; $B bench tangents --triangles 1000000 --runs 5 --threads 1 --json > "$OUT/bumpmap_tangents_ours_t1.json"
quiet; $B bench tangents --triangles 1000000 --runs 3 --threads 1 --mode mikktspace --json > "$OUT/bumpmap_tangents_mikktspace_t1.json"

echo "== renderer: torus 1024², 1 and 2 threads, ${RENDER_ROUNDS:=3} alternating rounds" >&2
# The machine's speed drifts by ±20 % within minutes, so the renderer and llvmpipe take turns and
# each round gives its own ratio; the script prints every round and the median.
rm -f "$OUT"/llvmpipe.*.json "$OUT"/bumpmap_render_*.json
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
for r in $(seq 1 "$RENDER_ROUNDS"); do
  quiet; python3 "$work/llvmpipe_torus.py" --size 1024 --frames 100 --repeats 3 --threads 1,2 --variants 1pass,3pass > "$OUT/llvmpipe.$r.log" 2>&1
  cp "$work/out/llvmpipe_results.json" "$OUT/llvmpipe.$r.json"
  for t in 2 1; do
    quiet; $B bench render --scene torus --size 1024 --technique kilgard --threads $t --frames 30 --runs 5 --json > "$OUT/bumpmap_render_kilgard_t$t.$r.json"
    quiet; $B bench render --scene torus --size 1024 --technique single-pass --threads $t --frames 30 --runs 5 --json > "$OUT/bumpmap_render_single_t$t.$r.json"
  done
  # The wgpu backend on lavapipe: Mesa's rasterizer under Vulkan, with llvmpipe's thread count.
  if [ "${GPU:-1}" = 1 ]; then
    quiet; LP_NUM_THREADS=2 $B bench render --backend gpu --scene torus --size 1024 --technique kilgard --threads 2 --frames 30 --runs 5 --json > "$OUT/bumpmap_render_gpu_kilgard.$r.json"
    quiet; LP_NUM_THREADS=2 $B bench render --backend gpu --scene torus --size 1024 --technique single-pass --threads 2 --frames 30 --runs 5 --json > "$OUT/bumpmap_render_gpu_single.$r.json"
  fi
done

python3 - "$OUT" <<'PY'
import json, sys, pathlib
out = pathlib.Path(sys.argv[1])
j = lambda n: json.loads((out / n).read_text())
np_, nm = j("numpy_normalmap.json"), j("bumpmap_normalmap.json")
print(f"normal map 4096²: numpy {np_['s_median']*1e3:.0f} ms, bumpmap {nm['median_ms']:.1f} ms "
      f"-> {np_['s_median']*1e3/nm['median_ms']:.1f}x; floor {nm['floor_median_ms']:.1f} ms -> {nm['ratio_to_floor']:.2f}x the floor")
if (out / "python_normalmap.json").exists():
    py = j("python_normalmap.json")
    per_round = ", ".join("%.2f" % r["ratio"] for r in py["rounds"])
    print(f"normal map 4096² from Python (bumpmap.mip_chain): median {py['python_median_ms']:.1f} ms, "
          f"{py['median_ratio']:.2f}x `bench normalmap` (rounds: {per_round}); "
          f"numpy {np_['s_median']*1e3:.0f} ms -> {np_['s_median']*1e3/py['python_median_ms']:.1f}x")
mk, ours, mikk = j("mikktspace.json"), j("bumpmap_tangents_ours.json"), j("bumpmap_tangents_mikktspace.json")
c = mk.get("mikktspace_c", {}).get("s_median")
if c:
    print(f"tangents 1M tris: C MikkTSpace {c*1e3:.0f} ms; bumpmap ours {ours['median_ms']:.0f} ms -> {c*1e3/ours['median_ms']:.2f}x; "
          f"bumpmap mikktspace {mikk['median_ms']:.0f} ms -> {c*1e3/mikk['median_ms']:.2f}x")
rounds = sorted(int(p.name.split(".")[1]) for p in out.glob("llvmpipe.*.json"))
median = lambda xs: sorted(xs)[len(xs) // 2]
table = []   # (work, peer, threads, ratio text) for the summary at the end

def render_ratio(name, peer, threads):
    """Each round's fps over llvmpipe's in the same round, printed; returns their median."""
    ratios = []
    for r in rounds:
        lp = {x["variant"]: x for x in j(f"llvmpipe.{r}.json") if str(x["threads"]) == str(threads)}
        ours = j(f"{name}.{r}.json")
        ratios.append(ours["fps"] / lp[peer]["fps_median"])
        print(f"render torus 1024² round {r} ({ours.get('backend', 'cpu')} {ours['technique']} vs llvmpipe {peer}, {threads} thread(s)): "
              f"{ours['fps']:.1f} fps vs {lp[peer]['fps_median']:.1f} fps -> {ratios[-1]:.2f}x")
    print(f"render torus 1024² {name.removeprefix('bumpmap_render_')} vs llvmpipe {peer}: median of {len(ratios)} rounds "
          f"{median(ratios):.2f}x (range {min(ratios):.2f}-{max(ratios):.2f}x)")
    return f"{median(ratios):.2f}× ({min(ratios):.2f}–{max(ratios):.2f})"

for technique, peer, work in [("kilgard", "3pass", "torus 1024², the paper's three passes"),
                              ("single", "1pass", "torus 1024², single pass")]:
    cells = [render_ratio(f"bumpmap_render_{technique}_t{t}", peer, t) for t in (1, 2)]
    table.append((work, f"llvmpipe `{peer}`", *cells))
for technique, peer in [("gpu_kilgard", "3pass"), ("gpu_single", "1pass")]:
    name = f"bumpmap_render_{technique}"
    if (out / f"{name}.{rounds[0]}.json").exists():
        table.append((f"torus 1024², {technique.replace('_', ' ')} on lavapipe", f"llvmpipe `{peer}`", "—", render_ratio(name, peer, 2)))

nm1 = j("bumpmap_normalmap_t1.json")
table.insert(0, ("4096² heights → normal map + 13 mips", "the memory floor (`bench normalmap --floor`)",
                 f"{nm1['ratio_to_floor']:.2f}× the floor", f"{nm['ratio_to_floor']:.2f}× the floor"))
if c:
    o1, m1 = j("bumpmap_tangents_ours_t1.json"), j("bumpmap_tangents_mikktspace_t1.json")
    table.insert(1, ("tangents of 1 M triangles", f"C MikkTSpace ({c*1e3:.0f} ms)",
                     f"{c*1e3/o1['median_ms']:.1f}×", f"{c*1e3/ours['median_ms']:.1f}×"))
    table.insert(2, ("the same in MikkTSpace mode (bit-identical)", "C MikkTSpace",
                     f"{c*1e3/m1['median_ms']:.2f}×", f"{c*1e3/mikk['median_ms']:.2f}×"))
print()
print("| work | peer | 1 thread | 2 threads |")
print("| --- | --- | --- | --- |")
for row in table:
    print("| " + " | ".join(row) + " |")
PY
