"""`bumpmap bake`'s maps seen by another renderer: Blender's Cycles (bpy) draws HIGH, and LOW with
each map, as its shading normals (each pixel's world-space normal after the normal map, through
Blender's own MikkTSpace tangents and Normal Map node), and the angles between them are
measured. A map baked for MikkTSpace's per-pixel decode (`--decode mikktspace`, the default)
should bring LOW as close to HIGH in Blender as Blender's own bake does.

    target/python-test-venv/bin/python scripts/bake_seen_in_blender.py [--size 1024]
        [--out target/bake-in-blender] [--json]

Needs the release `bumpmap` (cargo build --release) and bpy. The pairs: a wavy sphere onto a
32×16 sphere, and a wavy torus onto a 24×12 torus (coarse, so its tangent frames turn much
from vertex to vertex). Prints a table (or one JSON line with --json).
"""

import argparse
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np

# The pair is written and baked by Cycles as the speed benchmark does it.
from bench_bake_blender import bake_blender, grid, write_obj

REPO = Path(__file__).resolve().parents[1]
BUMPMAP = REPO / "target" / "release" / "bumpmap"
SIDE = 256


def sphere(waves):
    def point(u, v):
        theta, phi = u * 2 * np.pi, v * np.pi
        r = 1.0 + (0.02 * np.sin(8 * theta) * np.sin(6 * phi) if waves else 0.0)
        return np.stack([r * np.sin(phi) * np.cos(theta), r * np.sin(phi) * np.sin(theta), -r * np.cos(phi)], -1)

    return point


def torus(waves):
    def point(u, v):
        s, t = u * 2 * np.pi, v * 2 * np.pi
        r = 0.5 + (0.015 * np.sin(10 * s) * np.sin(4 * t) if waves else 0.0)
        ring = 1.2 + r * np.cos(t)
        return np.stack([ring * np.cos(s), ring * np.sin(s), r * np.sin(t)], -1)

    return point


def fresh_scene():
    import bpy

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2
    return scene


def import_obj(path):
    import bpy

    bpy.ops.wm.obj_import(filepath=str(path), forward_axis="Y", up_axis="Z")
    return bpy.data.objects[Path(path).stem]


def normal_material(name, map_path=None):
    """A material that shows the shading normal as colour, (n + 1) / 2: the geometry's, or the
    normal map's through Blender's Normal Map node (tangent space, the mesh's UV map)."""
    import bpy

    material = bpy.data.materials.new(name)
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    if map_path is None:
        normal = tree.nodes.new("ShaderNodeNewGeometry").outputs["Normal"]
    else:
        texture = tree.nodes.new("ShaderNodeTexImage")
        texture.image = bpy.data.images.load(str(map_path))
        texture.image.colorspace_settings.name = "Non-Color"
        texture.interpolation = "Linear"
        node = tree.nodes.new("ShaderNodeNormalMap")
        node.space = "TANGENT"
        tree.links.new(texture.outputs["Color"], node.inputs["Color"])
        normal = node.outputs["Normal"]
    half = tree.nodes.new("ShaderNodeVectorMath")
    half.operation = "MULTIPLY_ADD"
    half.inputs[1].default_value = (0.5, 0.5, 0.5)
    half.inputs[2].default_value = (0.5, 0.5, 0.5)
    tree.links.new(normal, half.inputs[0])
    emission = tree.nodes.new("ShaderNodeEmission")
    tree.links.new(half.outputs["Vector"], emission.inputs["Color"])
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(emission.outputs["Emission"], out.inputs["Surface"])
    return material


def normals_seen(mesh, map_path, out):
    """Cycles' shading normals of `mesh` (with `map_path` as its tangent-space normal map, or
    none), one sample a pixel at its centre, from the camera every render shares; and which
    pixels it covers."""
    import bpy

    scene = fresh_scene()
    scene.cycles.samples = 1
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 0.01
    scene.view_settings.view_transform = "Standard"
    scene.render.resolution_x = scene.render.resolution_y = SIDE
    scene.render.film_transparent = True
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    obj = import_obj(mesh)
    obj.data.materials.clear()
    obj.data.materials.append(normal_material("normals", map_path))
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    camera.location = (0.0, -5.0, 2.0)
    direction = -np.array(camera.location)
    camera.rotation_euler = (math.atan2(math.hypot(direction[0], direction[1]), -direction[2]), 0.0, 0.0)
    scene.camera = camera
    scene.render.filepath = str(out)
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(str(out))
    rgba = np.array(image.pixels[:], dtype=np.float64).reshape(SIDE, SIDE, 4)
    n = rgba[..., :3] * 2.0 - 1.0
    n /= np.linalg.norm(n, axis=-1, keepdims=True) + 1e-12
    return n, rgba[..., 3] > 0.999


def mean_angle(a, b):
    """The mean angle between two renders' normals over the pixels both cover, two pixels in
    from either silhouette."""
    (na, va), (nb, vb) = a, b
    inner = va & vb
    for shift in (-2, -1, 1, 2):
        inner &= np.roll(va & vb, shift, 0) & np.roll(va & vb, shift, 1)
    dots = np.clip((na[inner] * nb[inner]).sum(-1), -1.0, 1.0)
    return float(np.degrees(np.arccos(dots)).mean()), int(inner.sum())


def measure(name, surface, high_quads, low_quads, size, out):
    high, low = out / f"{name}_high.obj", out / f"{name}_low.obj"
    write_obj(high, *grid(*high_quads, surface(True)))
    write_obj(low, *grid(*low_quads, surface(False)))
    maps = {}
    for decode in ("mikktspace", "per-vertex"):
        maps[decode] = out / f"{name}_{decode}.png"
        subprocess.run([str(BUMPMAP), "bake", str(high), str(low), "-o", str(maps[decode]), "--size", str(size),
                        "--spp", "1", "--extrude", "0.1", "--max-distance", "0.1", "--decode", decode],
                       check=True, capture_output=True)
    maps["cycles"] = out / f"{name}_cycles.png"
    # Blender's own bake of the pair: selected to active, tangent space, the same cage.
    bake_blender(high, low, maps["cycles"], size, 1, 0.1, 2)
    target = normals_seen(high, None, out / f"{name}_high.exr")
    row = {"pair": name}
    for key, path in maps.items():
        row[key], row["pixels"] = mean_angle(target, normals_seen(low, path, out / f"{name}_{key}.exr"))
    row["without"], _ = mean_angle(target, normals_seen(low, None, out / f"{name}_plain.exr"))
    return row


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=1024)
    ap.add_argument("--out", type=Path, default=REPO / "target" / "bake-in-blender")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    rows = [
        measure("sphere", sphere, (400, 200), (32, 16), args.size, args.out),
        measure("torus", torus, (480, 240), (24, 12), args.size, args.out),
    ]
    if args.json:
        print(json.dumps(rows))
        return 0
    print("| pair | bumpmap, --decode mikktspace | bumpmap, --decode per-vertex | Cycles' own bake | LOW without a map | pixels |")
    print("| --- | --- | --- | --- | --- | --- |")
    for r in rows:
        print(f"| {r['pair']} | {r['mikktspace']:.3f}° | {r['per-vertex']:.3f}° | {r['cycles']:.3f}° | {r['without']:.3f}° | {r['pixels']} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
