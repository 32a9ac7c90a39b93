"""Blender: a normal map from an image's pixels, plugged into a material's Normal Map node.

Takes an image datablock holding heights (a greyscale bump image; a colour image's Rec. 709
luminance is used), makes a tangent-space normal map with bumpmap (green up: Blender's own
convention, so no channel is flipped), stores it as a new packed image in Non-Color, and wires
Image Texture -> Normal Map (tangent space) -> the Principled BSDF's Normal.

Install bumpmap into Blender's Python once (see the README), then either paste this into the
Scripting workspace and call `make_normal_map("bump", "Material")`, or run

    blender scene.blend --background --python blender_normal_map.py -- IMAGE MATERIAL [SCALE]

which also saves the .blend file.
"""

import sys

import bpy
import numpy as np

import bumpmap

# Rec. 709 luminance, as `bumpmap normalmap --channel luminance` weighs a colour image.
LUMINANCE = np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)


def image_heights(image):
    """The image's heights as an (H, W) float32 array, row 0 the image's top (bumpmap's order;
    Blender's pixel rows run from the bottom)."""
    width, height = image.size
    pixels = np.empty(width * height * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    rgba = pixels.reshape(height, width, 4)[::-1]
    return np.ascontiguousarray(rgba[..., :3] @ LUMINANCE, dtype=np.float32)


def make_normal_map(image_name, material_name, scale=4.0):
    """Makes `image_name`'s normal map and wires it into `material_name`; returns the new image."""
    source = bpy.data.images[image_name]
    normals = bumpmap.normal_map(image_heights(source), scale=scale)  # (H, W, 4) uint8
    height, width = normals.shape[:2]
    image = bpy.data.images.new(f"{image_name}_normal", width, height, alpha=False)
    # Normal maps are data, not colour: no sRGB transfer on the way to the shader.
    image.colorspace_settings.name = "Non-Color"
    image.pixels.foreach_set((normals[::-1].astype(np.float32) / 255.0).ravel())
    image.pack()

    material = bpy.data.materials[material_name]
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    bsdf = next(n for n in nodes if n.type == "BSDF_PRINCIPLED")
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = image
    normal_node = nodes.new("ShaderNodeNormalMap")
    normal_node.space = "TANGENT"
    normal_node.inputs["Strength"].default_value = 1.0
    links.new(texture.outputs["Color"], normal_node.inputs["Color"])
    links.new(normal_node.outputs["Normal"], bsdf.inputs["Normal"])
    return image


if __name__ == "__main__" and "--" in sys.argv:
    args = sys.argv[sys.argv.index("--") + 1 :]
    if len(args) not in (2, 3):
        sys.exit("usage: blender FILE.blend --background --python blender_normal_map.py -- IMAGE MATERIAL [SCALE]")
    made = make_normal_map(args[0], args[1], float(args[2]) if len(args) == 3 else 4.0)
    print(f"made {made.name} ({made.size[0]}x{made.size[1]}) and wired it into {args[1]}")
    if bpy.data.filepath:
        bpy.ops.wm.save_mainfile()
