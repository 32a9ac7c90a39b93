"""`bumpmap bake` against Blender's Cycles bake ("selected to active", cage extrusion, tangent
space), in one run: the same pair of meshes, the same map size and samples, both timed on this
machine, and both maps judged the same way — each drawn on LOW by `bumpmap render` and its
shading normals compared with HIGH's (photometric stereo from three diffuse renders, as
crates/bumpmap/tests/bake_synced.rs measures).

    target/python-test-venv/bin/python scripts/bench_bake_blender.py [--size 2048] [--spp 4]
        [--triangles 1000000] [--threads 2] [--out target/bench-bake]

Needs the release `bumpmap` (cargo build --release) and bpy (scripts/test_python.sh installs
Blender 5.0's into target/python-test-venv). Prints one JSON line and a table for BENCHMARKS.md.
Our time is the whole command (reading both OBJ files, the BVH, the bake, writing the files);
Blender's is the bake operator alone (its import is not counted).
"""

import argparse
import json
import math
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
BUMPMAP = REPO / "target" / "release" / "bumpmap"


def grid(nu, nv, point):
    """A (nu × nv)-quad grid of `point(u, v)` (arrays of u and v in [0, 1]), its texture
    coordinates as OBJ has them (v up), as (positions, uvs, faces), without the triangles a pole
    makes degenerate (two corners at one point)."""
    u, v = np.meshgrid(np.linspace(0.0, 1.0, nu + 1), np.linspace(0.0, 1.0, nv + 1))
    pos = point(u, v).reshape(-1, 3)
    uvs = np.stack([u, 1.0 - v], -1).reshape(-1, 2)
    idx = np.arange((nu + 1) * (nv + 1)).reshape(nv + 1, nu + 1)
    a, b, c, d = idx[:-1, :-1], idx[:-1, 1:], idx[1:, 1:], idx[1:, :-1]
    faces = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    p = pos[faces]
    area = np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)
    return pos, uvs, faces[area > 1e-12]


def sphere(nu, nv, waves):
    """A UV sphere of nu×nv quads, radius 1 (times 1 + 0.02·sin 8u·sin 6v with `waves`), as
    `grid` gives it."""

    def point(u, v):
        theta, phi = u * 2 * np.pi, v * np.pi
        r = 1.0 + (0.02 * np.sin(8 * theta) * np.sin(6 * phi) if waves else 0.0)
        return np.stack([r * np.sin(phi) * np.cos(theta), r * np.sin(phi) * np.sin(theta), r * np.cos(phi)], -1)

    return grid(nu, nv, point)


def vertex_normals(pos, faces):
    """Area-weighted vertex normals (what bumpmap computes for a file without them)."""
    p = pos[faces]
    face = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    sums = np.zeros_like(pos)
    for k in range(3):
        np.add.at(sums, faces[:, k], face)
    return sums / (np.linalg.norm(sums, axis=1, keepdims=True) + 1e-30)


def write_obj(path, pos, uvs, faces):
    """An OBJ with its normals (so Blender shades it smooth with the normals bumpmap reads)."""
    with open(path, "w") as f:
        np.savetxt(f, pos, fmt="v %.7f %.7f %.7f")
        np.savetxt(f, uvs, fmt="vt %.7f %.7f")
        np.savetxt(f, vertex_normals(pos, faces), fmt="vn %.7f %.7f %.7f")
        np.savetxt(f, np.repeat(faces + 1, 3, axis=1), fmt="f %d/%d/%d %d/%d/%d %d/%d/%d")


def bake_blender(high, low, out, size, spp, extrusion, threads):
    import bpy

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = spp
    scene.render.threads_mode = "FIXED"
    scene.render.threads = threads
    for path in (high, low):
        bpy.ops.wm.obj_import(filepath=str(path), forward_axis="Y", up_axis="Z")
    high_obj, low_obj = (bpy.data.objects[Path(p).stem] for p in (high, low))
    image = bpy.data.images.new("bake", width=size, height=size, float_buffer=False)
    material = bpy.data.materials.new("bake")
    material.use_nodes = True
    node = material.node_tree.nodes.new("ShaderNodeTexImage")
    node.image = image
    material.node_tree.nodes.active = node
    low_obj.data.materials.clear()
    low_obj.data.materials.append(material)
    bpy.ops.object.select_all(action="DESELECT")
    high_obj.select_set(True)
    low_obj.select_set(True)
    bpy.context.view_layer.objects.active = low_obj
    bake = scene.render.bake
    bake.use_selected_to_active = True
    bake.cage_extrusion = extrusion
    bake.max_ray_distance = 2 * extrusion
    bake.margin = 16
    bake.normal_space = "TANGENT"
    start = time.perf_counter()
    bpy.ops.object.bake(type="NORMAL")
    seconds = time.perf_counter() - start
    image.filepath_raw = str(out)
    image.file_format = "PNG"
    image.save()
    return seconds


def shading_normals(mesh, technique, lights, size=256):
    """Each pixel's normal from three diffuse renders by `bumpmap render` (None where dark)."""
    from PIL import Image

    images = []
    for k, light in enumerate(lights):
        png = Path(mesh).with_suffix(f".{technique}.{k}.png")
        subprocess.run([str(BUMPMAP), "render", "--scene", f"mesh:{mesh}", "--technique", technique,
                        "--eye", "0,-4,0.6", "--target", "0,0,0", "--light", "dir:{},{},{}".format(*light),
                        "--decal", "none", "--ambient", "0", "--diffuse", "1", "--specular", "0",
                        "--self-shadow", "off", "--size", str(size), "-o", str(png)], check=True, capture_output=True)
        images.append(np.asarray(Image.open(png))[..., 0].astype(np.float64) / 255.0)
    stack = np.stack(images, -1)
    l = np.array([np.array(x) / np.linalg.norm(x) for x in lights])
    n = stack @ np.linalg.inv(l).T
    n /= np.linalg.norm(n, axis=-1, keepdims=True) + 1e-12
    valid = stack.min(-1) > 0.1
    return n, valid


def angle(a, b):
    (na, va), (nb, vb) = a, b
    both = va & vb
    # Away from either silhouette: two pixels in from the edge of what both see.
    inner = both.copy()
    for dy in (-2, -1, 1, 2):
        inner &= np.roll(both, dy, 0)
    for dx in (-2, -1, 1, 2):
        inner &= np.roll(both, dx, 1)
    dots = np.clip((na[inner] * nb[inner]).sum(-1), -1, 1)
    return float(np.degrees(np.arccos(dots)).mean()), int(inner.sum())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=2048)
    ap.add_argument("--spp", type=int, default=4)
    ap.add_argument("--triangles", type=int, default=1_000_000)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", type=Path, default=REPO / "target" / "bench-bake")
    args = ap.parse_args()
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    nu = int(round(math.sqrt(args.triangles)))
    high, low = out / "high.obj", out / "low.obj"
    hp = sphere(nu, nu // 2, waves=True)
    write_obj(high, *hp)
    lp = sphere(32, 16, waves=False)
    write_obj(low, *lp)
    extrusion = 0.1

    start = time.perf_counter()
    subprocess.run([str(BUMPMAP), "bake", str(high), str(low), "-o", str(out / "ours.png"), "--size", str(args.size),
                    "--spp", str(args.spp), "--extrude", str(extrusion), "--max-distance", str(extrusion),
                    "--low-out", str(out / "low_ours.glb")], check=True, capture_output=True)
    ours = time.perf_counter() - start
    blender = bake_blender(high, low, out / "blender.png", args.size, args.spp, extrusion, args.threads)
    subprocess.run([str(BUMPMAP), "tangents", str(low), "--mode", "mikktspace", "--normal-map", str(out / "blender.png"),
                    "-o", str(out / "low_blender.glb")], check=True, capture_output=True)
    subprocess.run([str(BUMPMAP), "tangents", str(high), "-o", str(out / "high.glb")], check=True, capture_output=True)

    lights = [(0.0, -1.0, 0.35), (0.8, -1.0, -0.25), (-0.8, -1.0, -0.25)]
    target = shading_normals(out / "high.glb", "no-bump", lights)
    ours_angle, pixels = angle(target, shading_normals(out / "low_ours.glb", "single-pass", lights))
    blender_angle, _ = angle(target, shading_normals(out / "low_blender.glb", "single-pass", lights))
    result = {
        "bench": "bake", "high_triangles": int(len(hp[2])), "low_triangles": int(len(lp[2])), "size": args.size,
        "spp": args.spp, "threads": args.threads, "bumpmap_s": round(ours, 2), "blender_cycles_s": round(blender, 2),
        "speedup": round(blender / ours, 2), "bumpmap_mean_angle_deg": round(ours_angle, 3),
        "blender_mean_angle_deg": round(blender_angle, 3), "pixels": pixels,
    }
    print(json.dumps(result))
    print(f"| {args.size}², {args.spp} spp, {result['high_triangles']:,} triangles, {args.threads} threads "
          f"| {ours:.1f} s | {blender:.1f} s | {blender / ours:.1f}× | {ours_angle:.2f}° | {blender_angle:.2f}° |")


if __name__ == "__main__":
    sys.exit(main())
