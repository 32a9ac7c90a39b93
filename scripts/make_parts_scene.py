#!/usr/bin/env python3
"""Writes the glTF scenes `bench_parts.sh` times: the same 100 tiles (a 10x10 wall of gently
waved 16x16-quad patches, 51,200 triangles) as

  parts100.gltf  100 primitives (four meshes of 25, placed by four nodes) drawn with 20
                 materials, each its own 128x128 normal map and base colour;
  parts1.gltf    one primitive with one material: the floor a renderer's per-part cost is
                 measured against.

Standard library only (PNG by zlib), so it runs wherever the benchmark does.

    python3 scripts/make_parts_scene.py OUT_DIR
"""

import base64
import json
import math
import struct
import sys
import zlib
from pathlib import Path

TILES, QUADS, MATERIALS, TEX = 10, 16, 20, 128


def png(width, height, rgb_rows):
    """An RGB8 PNG of `rgb_rows` (a list of bytes objects, one per row)."""
    raw = b"".join(b"\x00" + row for row in rgb_rows)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b"")


def normal_map(k):
    """Material k's normal texture (glTF: green up): ridges at an angle and frequency of its own."""
    angle, freq = math.pi * k / MATERIALS, 2 + k % 5
    dx, dy = math.cos(angle), math.sin(angle)
    rows = []
    for y in range(TEX):
        row = bytearray()
        for x in range(TEX):
            s, t = (x + 0.5) / TEX, (y + 0.5) / TEX
            slope = 0.8 * math.cos(2 * math.pi * freq * (dx * s + dy * t))
            # Height gradient along s and t; +t runs down the image, glTF's green up.
            nx, ny, nz = -slope * dx, slope * dy, 1.0
            n = math.sqrt(nx * nx + ny * ny + nz * nz)
            row += bytes(round(127.5 * c / n + 127.5) for c in (nx, ny, nz))
        rows.append(bytes(row))
    return png(TEX, TEX, rows)


def base_color(k):
    r, g, b = (80 + (k * 53) % 170, 80 + (k * 97) % 170, 80 + (k * 31) % 170)
    rows = [bytes([r, g, b] * TEX) if (y // 16) % 2 else bytes([r // 2 + 60, g // 2 + 60, b // 2 + 60] * TEX) for y in range(TEX)]
    return png(TEX, TEX, rows)


def tile(i, j):
    """Tile (i, j)'s positions, normals, texture coordinates and indices."""
    pos, nor, uv, idx = [], [], [], []
    n = QUADS + 1
    for b in range(n):
        for a in range(n):
            u, v = a / QUADS, b / QUADS
            x, y = i + u - TILES / 2, j + v - TILES / 2
            z = 0.05 * math.sin(2 * x) * math.cos(2 * y)
            dzdx = 0.1 * math.cos(2 * x) * math.cos(2 * y)
            dzdy = -0.1 * math.sin(2 * x) * math.sin(2 * y)
            l = math.sqrt(dzdx * dzdx + dzdy * dzdy + 1)
            pos += [x, y, z]
            nor += [-dzdx / l, -dzdy / l, 1 / l]
            uv += [u, 1 - v]
    for b in range(QUADS):
        for a in range(QUADS):
            k = b * n + a
            idx += [k, k + 1, k + n + 1, k, k + n + 1, k + n]
    return pos, nor, uv, idx


class Writer:
    def __init__(self):
        self.bin, self.views, self.accessors = bytearray(), [], []

    def accessor(self, fmt, values, component, kind, count, extra=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        data = struct.pack("<%d%s" % (len(values), fmt), *values)
        self.views.append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        acc = {"bufferView": len(self.views) - 1, "componentType": component, "count": count, "type": kind}
        acc.update(extra or {})
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def primitive(self, tiles, material):
        pos, nor, uv, idx = [], [], [], []
        for i, j in tiles:
            p, n, t, x = tile(i, j)
            base = len(pos) // 3
            pos += p
            nor += n
            uv += t
            idx += [base + k for k in x]
        count = len(pos) // 3
        lo = [min(pos[c::3]) for c in range(3)]
        hi = [max(pos[c::3]) for c in range(3)]
        return {
            "attributes": {
                "POSITION": self.accessor("f", pos, 5126, "VEC3", count, {"min": lo, "max": hi}),
                "NORMAL": self.accessor("f", nor, 5126, "VEC3", count),
                "TEXCOORD_0": self.accessor("f", uv, 5126, "VEC2", count),
            },
            "indices": self.accessor("I", idx, 5125, "SCALAR", len(idx)),
            "material": material,
        }


def document(writer, meshes, nodes, materials):
    images = []
    for k in range(materials):
        images.append({"uri": "data:image/png;base64," + base64.b64encode(normal_map(k)).decode()})
        images.append({"uri": "data:image/png;base64," + base64.b64encode(base_color(k)).decode()})
    return {
        "asset": {"version": "2.0", "generator": "bumpmap scripts/make_parts_scene.py"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": [
            {
                "name": "m%d" % k,
                "normalTexture": {"index": 2 * k},
                "pbrMetallicRoughness": {"baseColorTexture": {"index": 2 * k + 1}, "metallicFactor": 0},
            }
            for k in range(materials)
        ],
        "textures": [{"source": i} for i in range(len(images))],
        "images": images,
        "buffers": [{"byteLength": len(writer.bin), "uri": "data:application/octet-stream;base64," + base64.b64encode(writer.bin).decode()}],
        "bufferViews": writer.views,
        "accessors": writer.accessors,
    }


def main():
    out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    out.mkdir(parents=True, exist_ok=True)
    tiles = [(i, j) for j in range(TILES) for i in range(TILES)]
    # 100 primitives: four meshes of 25 tiles (a quarter of the wall each), one node each.
    w = Writer()
    meshes = []
    for q in range(4):
        quarter = tiles[q * 25 : (q + 1) * 25]
        meshes.append({"primitives": [w.primitive([t], (q * 25 + k) % MATERIALS) for k, t in enumerate(quarter)]})
    nodes = [{"mesh": q} for q in range(4)]
    (out / "parts100.gltf").write_text(json.dumps(document(w, meshes, nodes, MATERIALS)))
    w = Writer()
    (out / "parts1.gltf").write_text(json.dumps(document(w, [{"primitives": [w.primitive(tiles, 0)]}], [{"mesh": 0}], 1)))
    print("wrote %s and %s" % (out / "parts100.gltf", out / "parts1.gltf"))


if __name__ == "__main__":
    main()
