"""Blender: a normal map from an image's pixels, plugged into a material's Normal Map node.

Takes an image holding heights (a greyscale bump image; a colour image's Rec. 709 luminance is
used), makes a tangent-space normal map with bumpmap (green up: Blender's own convention, so no
channel is flipped), stores it as a packed image in Non-Color, and wires
Image Texture -> Normal Map (tangent space) -> the Principled BSDF's Normal.

Running it again replaces what it made before instead of adding to it: the image
``NAME_normal`` gets the new pixels (and size), and the two nodes it names ``bumpmap normal
texture`` and ``bumpmap normal map`` are reused. Nothing else in the material changes.

The heights can be an image already in the .blend (by name) or an image file (by path, loaded
once). An image whose pixels Blender cannot read (its file moved, never saved, or a render
result) is refused with the reason, not a bare ``KeyError``.

Install bumpmap into Blender's Python once (see the README), then either paste this into the
Scripting workspace and call ``make_normal_map("bump", "Material")``, or run

    blender scene.blend --background --python blender_normal_map.py -- IMAGE MATERIAL [SCALE]

which also saves the .blend file. Written for Blender 4.2 to 5.x (no deprecated API on 5.x).
"""

import os
import sys

import bpy
import numpy as np

import bumpmap

# Rec. 709 luminance, as `bumpmap normalmap --channel luminance` weighs a colour image.
LUMINANCE = np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)
TEXTURE_NODE = "bumpmap normal texture"
NORMAL_NODE = "bumpmap normal map"


def find_image(image):
    """The image datablock `image` names, or the image file it is the path of (loaded once);
    a `LookupError` naming what exists when it is neither."""
    if image in bpy.data.images:
        return bpy.data.images[image]
    if os.path.isfile(image):
        return bpy.data.images.load(image, check_existing=True)
    names = ", ".join(sorted(i.name for i in bpy.data.images)) or "none"
    raise LookupError(f"no image named {image!r} in this .blend and no such file (images: {names})")


def image_heights(image):
    """The image's heights as an (H, W) float32 array, row 0 the image's top (bumpmap's order;
    Blender's pixel rows run from the bottom)."""
    width, height = image.size
    if width == 0 or height == 0 or image.channels == 0:
        where = f"its file {bpy.path.abspath(image.filepath)} cannot be read" if image.filepath else "it has no file"
        raise ValueError(f"image {image.name!r} has no pixels Blender can read ({where}); "
                         "open or save it first, or pass the path of the file")
    pixels = np.empty(width * height * image.channels, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    pixels = pixels.reshape(height, width, image.channels)[::-1]
    rgb = pixels[..., :3] if image.channels >= 3 else np.repeat(pixels[..., :1], 3, axis=2)
    return np.ascontiguousarray(rgb @ LUMINANCE, dtype=np.float32)


def store_normal_map(name, normals):
    """`normals` ((H, W, 4) uint8) as the packed Non-Color image `name`, made or replaced."""
    height, width = normals.shape[:2]
    image = bpy.data.images.get(name)
    if image is None:
        image = bpy.data.images.new(name, width, height, alpha=False)
    elif tuple(image.size) != (width, height):
        image.scale(width, height)
    # Normal maps are data, not colour: no sRGB transfer on the way to the shader.
    image.colorspace_settings.name = "Non-Color"
    image.pixels.foreach_set((normals[::-1].astype(np.float32) / 255.0).ravel())
    image.pack()
    return image


def node(nodes, name, kind):
    """The node called `name` of type `kind`, made if the material has none."""
    found = nodes.get(name)
    if found is not None and found.bl_idname == kind:
        return found
    if found is not None:
        nodes.remove(found)
    made = nodes.new(kind)
    made.name = made.label = name
    return made


def make_normal_map(image_name, material_name, scale=4.0):
    """Makes the normal map of `image_name` (an image's name or an image file) and wires it into
    `material_name`'s Principled BSDF; returns the image it wrote."""
    source = find_image(image_name)
    if material_name not in bpy.data.materials:
        names = ", ".join(sorted(m.name for m in bpy.data.materials)) or "none"
        raise LookupError(f"no material named {material_name!r} (materials: {names})")
    material = bpy.data.materials[material_name]
    if material.node_tree is None:
        raise ValueError(f"material {material_name!r} has no shader nodes (before Blender 5.0: tick Use Nodes)")
    bsdf = next((n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED"), None)
    if bsdf is None:
        raise ValueError(f"material {material_name!r} has no Principled BSDF to take the normal")

    normals = bumpmap.normal_map(image_heights(source), scale=scale)  # (H, W, 4) uint8
    image = store_normal_map(f"{source.name}_normal", normals)

    nodes, links = material.node_tree.nodes, material.node_tree.links
    texture = node(nodes, TEXTURE_NODE, "ShaderNodeTexImage")
    texture.image = image
    texture.location = (bsdf.location.x - 520, bsdf.location.y - 320)
    normal_node = node(nodes, NORMAL_NODE, "ShaderNodeNormalMap")
    normal_node.space = "TANGENT"
    normal_node.inputs["Strength"].default_value = 1.0
    normal_node.location = (bsdf.location.x - 240, bsdf.location.y - 320)
    links.new(texture.outputs["Color"], normal_node.inputs["Color"])
    links.new(normal_node.outputs["Normal"], bsdf.inputs["Normal"])
    return image


if __name__ == "__main__" and "--" in sys.argv:
    args = sys.argv[sys.argv.index("--") + 1 :]
    if len(args) not in (2, 3):
        sys.exit("usage: blender FILE.blend --background --python blender_normal_map.py -- IMAGE MATERIAL [SCALE]")
    try:
        made = make_normal_map(args[0], args[1], float(args[2]) if len(args) == 3 else 4.0)
    except (LookupError, ValueError) as e:
        sys.exit(f"error: {e}")
    print(f"made {made.name} ({made.size[0]}x{made.size[1]}) and wired it into {args[1]}")
    if bpy.data.filepath:
        bpy.ops.wm.save_mainfile()
