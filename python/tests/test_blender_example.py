"""The Blender example against the real `bpy` module (Blender 5.0 as a Python module, from PyPI),
in a child process with a fresh Blender: it makes the normal map of a grey height image, wires
it into a material's Principled BSDF without touching a deprecated API (DeprecationWarning is an
error there), replaces rather than piles up on a second run, keeps the image through a save and
reload of the .blend (packed), takes an image file's path, and refuses a missing image, a missing
material and an image whose file is gone with a clear error.

bpy has wheels for one CPython version (3.11 for Blender 5.0) on x86-64 Linux, Windows and macOS;
scripts/test_python.sh installs it there. Elsewhere the test skips, saying so."""

import importlib.util
import platform
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "blender_normal_map.py"
BPY_RUNS_HERE = sys.version_info[:2] == (3, 11) and platform.machine() in ("x86_64", "AMD64")

HAS_BPY = importlib.util.find_spec("bpy") is not None

SCRIPT = """
import importlib.util, os, sys, warnings
import numpy as np
import bpy
import bumpmap
from PIL import Image

example_path, tmp = sys.argv[1], sys.argv[2]
spec = importlib.util.spec_from_file_location("blender_normal_map", example_path)
example = importlib.util.module_from_spec(spec)
spec.loader.exec_module(example)

bpy.ops.wm.read_factory_settings(use_empty=True)
heights = bumpmap.read_height_field("dimples@32").astype(np.float32)  # row 0 at the top
bump = bpy.data.images.new("bump", 32, 32)
rgba = np.repeat(heights[::-1, :, None], 4, axis=2)  # Blender's rows run bottom first
rgba[..., 3] = 1
bump.pixels.foreach_set(rgba.ravel())
material = bpy.data.materials.new("Material")
material.use_fake_user = True  # kept through the save below without an object using it
assert material.node_tree is not None, "Blender 5 materials have nodes"

def written(image):
    px = np.empty(len(image.pixels), np.float32)
    image.pixels.foreach_get(px)
    return px.reshape(image.size[1], image.size[0], 4)[::-1]

def expect(image, scale):
    want = bumpmap.normal_map(heights, scale=scale).astype(np.float32) / 255
    assert np.abs(written(image) - want).max() <= 1.01 / 255, "pixels are bumpmap's normal map"

with warnings.catch_warnings():
    warnings.simplefilter("error", DeprecationWarning)
    made = example.make_normal_map("bump", "Material", scale=6.0)
    assert made.name == "bump_normal" and made.colorspace_settings.name == "Non-Color" and made.packed_file
    expect(made, 6.0)
    tree = material.node_tree
    before = sorted(n.bl_idname for n in tree.nodes), len(tree.links), len(bpy.data.images)
    again = example.make_normal_map("bump", "Material", scale=2.0)  # a second run replaces
    after = sorted(n.bl_idname for n in tree.nodes), len(tree.links), len(bpy.data.images)
assert again == made and before == after, (before, after)
expect(made, 2.0)
assert before[0] == ["ShaderNodeBsdfPrincipled", "ShaderNodeNormalMap", "ShaderNodeOutputMaterial", "ShaderNodeTexImage"]
bsdf = next(n for n in tree.nodes if n.type == "BSDF_PRINCIPLED")
into = bsdf.inputs["Normal"].links
assert len(into) == 1 and into[0].from_node.bl_idname == "ShaderNodeNormalMap" and into[0].from_node.space == "TANGENT"
tex = into[0].from_node.inputs["Color"].links[0].from_node
assert tex.bl_idname == "ShaderNodeTexImage" and tex.image == made

# Saved and opened again: the normal map is packed into the .blend, so it comes back.
blend = os.path.join(tmp, "scene.blend")
bpy.ops.wm.save_as_mainfile(filepath=blend)
bpy.ops.wm.open_mainfile(filepath=blend)
expect(bpy.data.images["bump_normal"], 2.0)

# An image file by its path.
Image.fromarray(np.round(heights * 255).astype(np.uint8)).save(os.path.join(tmp, "h.png"))
from_file = example.make_normal_map(os.path.join(tmp, "h.png"), "Material", scale=6.0)
assert from_file.name == "h.png_normal" and from_file.size[:] == (32, 32)

# What must fail, failing clearly.
for image, material_name, words in [
    ("nope", "Material", "no image named 'nope'"),
    (os.path.join(tmp, "h.png"), "Nope", "no material named 'Nope'"),
]:
    try:
        example.make_normal_map(image, material_name)
    except LookupError as e:
        assert words in str(e), e
    else:
        raise AssertionError(f"{image}, {material_name} was accepted")
gone = bpy.data.images.load(os.path.join(tmp, "h.png"), check_existing=False)
gone.name = "gone"
os.remove(os.path.join(tmp, "h.png"))
gone.reload()
try:
    example.make_normal_map("gone", "Material")
except ValueError as e:
    assert "has no pixels" in str(e) and "h.png cannot be read" in str(e), e
else:
    raise AssertionError("an image whose file is gone was accepted")
print("blender example ok")
"""


@pytest.mark.skipif(not HAS_BPY and not BPY_RUNS_HERE,
                    reason=f"bpy (Blender 5.0) has no wheel for Python {platform.python_version()} on {platform.machine()}")
def test_the_example_in_real_blender(tmp_path):
    assert HAS_BPY, "bpy is not installed, though Blender 5.0's wheel fits this Python: scripts/test_python.sh installs it"
    done = subprocess.run([sys.executable, "-c", textwrap.dedent(SCRIPT), str(EXAMPLE), str(tmp_path)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0 and "blender example ok" in done.stdout, done.stdout[-3000:] + done.stderr[-3000:]
