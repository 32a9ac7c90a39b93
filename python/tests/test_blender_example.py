"""The Blender example against a stand-in for the few `bpy` calls it makes (Blender itself is
not installed here): it reads an image's pixels bottom row first, writes the normal map bumpmap
makes from them the same way, and wires the nodes."""

import importlib.util
import sys
import types
from pathlib import Path

import numpy as np

import bumpmap

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "blender_normal_map.py"


class Pixels:
    def __init__(self, values):
        self.values = values

    def foreach_get(self, out):
        out[:] = self.values

    def foreach_set(self, values):
        self.values = np.asarray(values, dtype=np.float32).copy()


class Image:
    def __init__(self, name, width, height, pixels=None):
        self.name, self.size = name, (width, height)
        self.pixels = Pixels(pixels if pixels is not None else np.zeros(width * height * 4, np.float32))
        self.colorspace_settings = types.SimpleNamespace(name="sRGB")
        self.packed = False

    def pack(self):
        self.packed = True


class Socket(types.SimpleNamespace):
    pass


class Node:
    def __init__(self, kind):
        self.type = kind
        self.inputs = {k: Socket(default_value=None, node=self, name=k) for k in ("Color", "Strength", "Normal")}
        self.outputs = {k: Socket(node=self, name=k) for k in ("Color", "Normal")}


class Nodes(list):
    def new(self, kind):
        node = Node(kind)
        self.append(node)
        return node


def fake_bpy(images):
    material = types.SimpleNamespace(use_nodes=False, node_tree=types.SimpleNamespace(nodes=Nodes([Node("BSDF_PRINCIPLED")]), links=[]))
    material.node_tree.links = types.SimpleNamespace(made=[], new=lambda a, b: material.node_tree.links.made.append((a, b)))

    class ImageTable(dict):
        def new(self, name, width, height, alpha=True):
            self[name] = Image(name, width, height)
            return self[name]

    bpy = types.ModuleType("bpy")
    bpy.data = types.SimpleNamespace(images=ImageTable(images), materials={"Material": material}, filepath="")
    return bpy, material


def test_the_example_makes_and_wires_the_normal_map(monkeypatch):
    heights = bumpmap.read_height_field("dimples@32")  # float32, row 0 at the top
    # Blender keeps rows bottom first, RGBA floats: a grey image of these heights.
    rgba = np.repeat(heights[::-1, :, None], 4, axis=2)
    rgba[..., 3] = 1
    bpy, material = fake_bpy({"bump": Image("bump", 32, 32, rgba.ravel().astype(np.float32))})
    monkeypatch.setitem(sys.modules, "bpy", bpy)
    spec = importlib.util.spec_from_file_location("blender_normal_map", EXAMPLE)
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)

    made = example.make_normal_map("bump", "Material", scale=6.0)
    assert made.colorspace_settings.name == "Non-Color" and made.packed
    written = made.pixels.values.reshape(32, 32, 4)[::-1]
    # Luminance of a grey pixel is the grey value (to float rounding): the map bumpmap makes
    # from the heights themselves, within one step of 8 bits.
    expected = bumpmap.normal_map(heights, scale=6.0).astype(np.float32) / 255
    assert np.abs(written - expected).max() <= 1.01 / 255
    kinds = [n.type for n in material.node_tree.nodes]
    assert kinds == ["BSDF_PRINCIPLED", "ShaderNodeTexImage", "ShaderNodeNormalMap"]
    links = [(a.node.type, a.name, b.node.type, b.name) for a, b in material.node_tree.links.made]
    assert links == [("ShaderNodeTexImage", "Color", "ShaderNodeNormalMap", "Color"),
                     ("ShaderNodeNormalMap", "Normal", "BSDF_PRINCIPLED", "Normal")]
    assert material.node_tree.nodes[2].space == "TANGENT"
