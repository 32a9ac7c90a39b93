"""Shared helpers: the command line to compare against, and independent readers of what it
writes (pypng for PNG, a few lines of struct for GLB)."""

import json
import os
import struct
import subprocess
from pathlib import Path

import numpy as np
import png
import pytest

REPO = Path(__file__).resolve().parents[2]


def cli_path() -> Path:
    """The `bumpmap` executable the results are compared with: $BUMPMAP_CLI, else the release
    build in this repository (scripts/test builds it)."""
    path = Path(os.environ.get("BUMPMAP_CLI", REPO / "target" / "release" / "bumpmap"))
    if not path.is_file():
        pytest.fail(f"no bumpmap executable at {path}: build it (cargo build --release) or set BUMPMAP_CLI")
    return path


@pytest.fixture(scope="session")
def cli():
    """Runs `bumpmap ARGS...`, failing the test with its stderr if it fails."""
    exe = cli_path()

    def run(*args):
        done = subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True)
        assert done.returncode == 0, f"bumpmap {' '.join(map(str, args))} failed:\n{done.stderr}"
        return done

    return run


def read_png(path) -> np.ndarray:
    """A PNG as an (H, W, C) array of uint8 or uint16, by pypng (not by bumpmap)."""
    width, height, rows, info = png.Reader(filename=str(path)).asDirect()
    planes = info["planes"]
    dtype = np.uint16 if info["bitdepth"] > 8 else np.uint8
    return np.vstack([np.asarray(r, dtype=dtype) for r in rows]).reshape(height, width, planes)


def read_glb(path) -> dict:
    """A GLB's first primitive as arrays: POSITION, NORMAL, TEXCOORD_0, TANGENT and indices."""
    data = Path(path).read_bytes()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    assert magic == b"glTF" and version == 2 and length == len(data)
    json_len, json_type = struct.unpack_from("<II", data, 12)
    assert json_type == 0x4E4F534A
    doc = json.loads(data[20 : 20 + json_len])
    bin_start = 20 + json_len + 8
    components = {5126: np.float32, 5125: np.uint32, 5123: np.uint16}
    widths = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}

    def accessor(i):
        acc = doc["accessors"][i]
        view = doc["bufferViews"][acc["bufferView"]]
        dtype = np.dtype(components[acc["componentType"]])
        width = widths[acc["type"]]
        start = bin_start + view.get("byteOffset", 0) + acc.get("byteOffset", 0)
        stride = view.get("byteStride", dtype.itemsize * width)
        assert stride == dtype.itemsize * width, "tightly packed"
        count = acc["count"] * width
        return np.frombuffer(data, dtype=dtype, count=count, offset=start).reshape(acc["count"], width)

    prim = doc["meshes"][0]["primitives"][0]
    out = {name: accessor(i) for name, i in prim["attributes"].items()}
    out["indices"] = accessor(prim["indices"]).reshape(-1, 3).astype(np.uint32)
    return out


def write_gltf(path, positions, normals, uvs, indices):
    """A glTF with one primitive, its buffer a data URI: what `bumpmap tangents` reads."""
    import base64

    parts = [
        np.ascontiguousarray(positions, dtype="<f4").tobytes(),
        np.ascontiguousarray(normals, dtype="<f4").tobytes(),
        np.ascontiguousarray(uvs, dtype="<f4").tobytes(),
        np.ascontiguousarray(indices, dtype="<u4").tobytes(),
    ]
    views, offset = [], 0
    for p in parts:
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(p)})
        offset += len(p)
    n = len(positions)
    doc = {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": offset, "uri": "data:application/octet-stream;base64," + base64.b64encode(b"".join(parts)).decode()}],
        "bufferViews": views,
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3",
             "min": np.min(positions, 0).tolist(), "max": np.max(positions, 0).tolist()},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": n, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5125, "count": int(np.size(indices)), "type": "SCALAR"},
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }
    Path(path).write_text(json.dumps(doc))


def wavy_grid(nx=24, ny=16, mirror_half=True):
    """A bumpy textured grid: positions, normals, uvs, indices; with `mirror_half`, the right
    half's texture is mirrored in u, as artists mirror a symmetric model's UVs."""
    xs, ys = np.meshgrid(np.linspace(0, 1, nx + 1), np.linspace(0, 1, ny + 1))
    z = 0.08 * np.sin(6 * xs) * np.cos(5 * ys)
    positions = np.stack([xs, ys, z], -1).reshape(-1, 3).astype(np.float32)
    dzdx = 0.08 * 6 * np.cos(6 * xs) * np.cos(5 * ys)
    dzdy = -0.08 * 5 * np.sin(6 * xs) * np.sin(5 * ys)
    normals = np.stack([-dzdx, -dzdy, np.ones_like(xs)], -1)
    normals = (normals / np.linalg.norm(normals, axis=-1, keepdims=True)).reshape(-1, 3).astype(np.float32)
    u = np.where(xs > 0.5, 1 - xs, xs) if mirror_half else xs
    uvs = np.stack([u, 1 - ys], -1).reshape(-1, 2).astype(np.float32)
    idx = []
    for j in range(ny):
        for i in range(nx):
            a = j * (nx + 1) + i
            b, c, d = a + 1, a + nx + 1, a + nx + 2
            idx += [[a, b, d], [a, d, c]]
    return positions, normals, uvs, np.array(idx, dtype=np.uint32)
