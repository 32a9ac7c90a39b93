"""bumpmap: bump mapping as Kilgard (2000), the Cg Tutorial (ch. 8) and Peercy et al. (1997)
describe it, for Python: normal maps and mip chains from height fields, tangent frames, and
renders of every technique of the papers, NumPy arrays in and out.

The functions take the options of the ``bumpmap`` command line as keyword arguments, with the
same names (``-`` becomes ``_``: ``--y-convention`` is ``y_convention=``), values and defaults,
as Python values (numbers, tuples for vectors, words of closed sets, paths, arrays), and they
make the same bytes the command writes from the same options:

- ``normal_map(heights, **options)``: an (H, W) height field -> an (H, W, 4) normal map
  (``bumpmap normalmap``);
- ``mip_chain(heights, **options)``: the same with every smaller level, the length of the
  averaged normal in alpha (Kilgard §2.4.2);
- ``height_mips(heights, **options)``: the heights as the parallax techniques read them: their
  levels and min–max levels (``bumpmap normalmap --height-out``);
- ``write_heights(path, heights, **options)``: the same written as the files ``--height-out``
  writes, which ``render --height-map`` and the command line's parallax techniques read;
- ``horizon_maps(heights, **options)``: the horizon map, ambient occlusion and bent normals
  (``bumpmap normalmap --horizon-out --ao-out --bent-normals-out``);
- ``roughness_map(heights, **options)``: the roughness map, every level
  (``bumpmap normalmap --mips --roughness-out``);
- ``lean_moments(heights, **options)``: LEAN mapping's moments, every level
  (``bumpmap normalmap --lean-out``);
- ``read_height_field(path, **options)``: an image file or a preset (``"bricks@512"``);
- ``write_texture(path, levels, **options)``: PNG (``.mip1.png``, ... beside level 0), DDS or
  KTX2, BC5/BC7 included;
- ``read_texture(path)``: what ``write_texture`` wrote (or any PNG, DDS, KTX2), read back: every
  level as arrays, the format and the Y convention the texels show;
- ``tangents(positions, normals, uvs, indices, **options)``: tangent frames with glTF's ``w``
  (``bumpmap tangents``);
- ``render(**options)``: any scene and technique of the catalogue on the CPU or GPU
  (``bumpmap render``) -> an (H, W, 4) uint8 image;
- ``Renderer(backend="cpu")``: a backend opened once; ``renderer.prepare(**options)`` sets up
  a ``Scene`` once (the options of ``render``) and ``scene.render(light=(x, y, z), eye=...)``
  draws frame after frame of it with the light or the eye moved, the maps and the GPU's
  device kept;
- ``compare(output=None, **options)``: every technique against the reference
  (``bumpmap compare``) -> the results as a dict;
- ``techniques()``: the catalogue, name by name;
- ``inspect(source)``: what a normal map (a file or an array) is: DirectX or OpenGL, a normal
  map at all, its mips, its seam (``bumpmap inspect --json``) -> a dict;
- ``height_from_normals(normals, **options)``: a normal map's slopes integrated back into
  heights (``bumpmap height``) -> an (H, W) float32 array.

``NormalMap`` keeps a map's levels and Y convention together (made from heights, read from a
file, written, inspected, integrated back into heights, drawn). ``render`` and
``Renderer.prepare`` take a ``Mesh`` (arrays) as the ``scene``, a ``NormalMap`` as the
``normal_map``, and a NumPy array where the command line takes a file, for
``normal_map`` ((H, W, 4) uint8 or uint16, or a list of levels), ``height_field`` ((H, W)) and
``decal`` ((H, W, 4) uint8): the array is used exactly as the file holding it would be.

Warnings (heights clamped, a roughness map of one level, ...) are issued through ``warnings`` as
``BumpmapWarning``; notes (what a glTF material gave, a technique ``compare`` skipped, the CPU
taken where ``backend="auto"`` found no GPU) go to the ``bumpmap`` logger at INFO. ``render``,
``compare``, ``bake`` and ``horizon_maps`` take ``progress=``, a function told ``(done, total)``
as the work advances.

Errors are exceptions carrying the library's message: ``ValueError`` for values, ``TypeError``
for arrays of the wrong dtype or options that do not exist, ``OSError`` for files
(``FileNotFoundError`` for a missing one), ``RuntimeError`` for a missing GPU. Long work
releases the GIL, and Ctrl-C interrupts it (``KeyboardInterrupt``; a file being written is
then not written at all).
"""

from __future__ import annotations

import inspect as _inspect

from ._native import load as _load_native

# The build for this processor: x86-64-v3 where it runs, else baseline x86-64 (see _native).
_bumpmap = _load_native()
del _load_native

__version__ = _bumpmap.__version__
#: The x86-64 level of the native module loaded: ``"x86-64-v3"`` or ``"x86-64"``.
native_build: str = _bumpmap.built_for()
#: The category of bumpmap's warnings (a ``UserWarning``).
BumpmapWarning = _bumpmap.BumpmapWarning

__all__ = [
    "BumpmapWarning",
    "normal_map",
    "mip_chain",
    "height_mips",
    "write_heights",
    "horizon_maps",
    "roughness_map",
    "lean_moments",
    "read_height_field",
    "write_texture",
    "read_texture",
    "tangents",
    "bake",
    "blend_normals",
    "render",
    "compare",
    "techniques",
    "inspect",
    "height_from_normals",
    "Mesh",
    "NormalMap",
    "Renderer",
    "Scene",
    "__version__",
]


def _is_number(text: str) -> bool:
    try:
        float(text)
        return True
    except ValueError:
        return False


def _options_doc(function: str) -> str:
    """The options ``function`` takes, as its docstring lists them, from the command line's own
    help texts and defaults."""
    lines = ["", "", "Options (keyword arguments; the command line's, with its defaults):", ""]
    for name, default, help_text, choices, flag in _bumpmap.options(function):
        if flag:
            head = f"{name}: bool = False"
        elif default is None:
            head = f"{name} = None"
        else:
            head = f"{name} = {_default(default)!r}"
        lines.append(f"    {head}")
        # The help, then each value's meaning where the set gives one ("\n- name: meaning").
        text, *meanings = help_text.split("\n- ")
        text = " ".join(text.split())
        if text:
            lines.append(f"        {text}")
        if meanings:
            lines.append("        One of:")
            lines.extend(f"          - {' '.join(m.split())}" for m in meanings)
        elif choices:
            lines.append(f"        One of: {', '.join(choices)}.")
    return "\n".join(lines) + "\n"


def normal_map(heights, **options):
    """A tangent-space normal map from a height field (Kilgard §2.3), as
    ``bumpmap normalmap IN -o OUT.png`` makes it.

    heights: an (H, W) numpy array: uint8 (h = b/255), uint16 (h = v/65535) or float32 (h in
    [0, 1]), row 0 first (texture coordinate t = 0, the image's top as displayed), as
    ``read_height_field`` returns it. Other dtypes are refused (convert float64 with
    ``.astype(numpy.float32)``); views that are not contiguous and big-endian arrays are read as
    they are.

    Returns an (H, W, 4) array: uint8, or uint16 with ``bits=16``; RGB is the unit normal
    (green up the image with the default ``y_convention``), alpha 255.
    """
    return _bumpmap.normal_map(heights, options)


def mip_chain(heights, **options):
    """A normal map and every smaller level down to 1x1, as
    ``bumpmap normalmap IN -o OUT.png --mips`` makes them.

    heights: as for ``normal_map``. With the default ``mip_mode="length-in-alpha"``, each
    smaller level stores the normalized mean of the normals it covers in RGB and the mean's
    length in alpha (Kilgard §2.4.2): what keeps a bumpy surface from looking too bright at a
    distance. Returns a list of (H, W, 4) arrays, level 0 first.
    """
    return _bumpmap.mip_chain(heights, options)


def height_mips(heights, **options):
    """The heights as the parallax techniques (``pom``, ``height-exact``, ...) read them, as
    ``bumpmap normalmap IN --height-out H`` stores them.

    heights: as for ``normal_map``, 1 on the surface and 0 at ``depth`` below it (values outside
    [0, 1] are clamped, with a warning on stderr). Returns ``(levels, minmax)``: ``levels`` a list
    of (H, W) float32 arrays, level 0 the heights rounded to ``bits``, each smaller level the mean
    of the texels it covers; ``minmax`` a list of (H, W, 2) float32 arrays, level 0 one texel per
    cell of the heights' C1 interpolant with its lower and upper bound, each smaller level the
    bounds of the cells it covers: what ``technique="height-exact"`` walks.
    """
    return _bumpmap.height_mips(heights, options)


def write_heights(path, heights, **options):
    """The heights written as ``bumpmap normalmap IN --height-out PATH`` writes them, all files
    or none: what ``height_mips`` returns, stored by ``path``'s extension. ``.png``: the levels
    as gray PNGs (``H.png``, ``H.mip1.png``, ...) and the min–max levels as 16-bit RGB
    (``H.minmax.png``, ...); ``.ktx2`` or ``.dds``: one file of every level (``R8_UNORM`` or
    ``R16_UNORM`` by ``bits``) and ``H.minmax.ktx2`` (``R16G16_UNORM``). Bounds are rounded
    outward, so they still bound the stored heights' interpolant. ``render(height_map=path)``
    and ``bumpmap render --height-map`` read them back. Returns the paths written.
    """
    return _bumpmap.write_heights(path, heights, options)


def horizon_maps(heights, **options):
    """The horizon map (Max 1988; Sloan & Cohen 2000) and what it gives, as
    ``bumpmap normalmap IN --horizon-out H --ao-out A --bent-normals-out B`` makes them.

    heights: as for ``normal_map``; ``scale`` is the normal map's and the depth, in texels, the
    heights are taken at. Returns a dict: ``"horizons"``, a list of (H, W, 8) float32 arrays,
    level 0 first, each value ``atan(rise) / 90°`` with the rise in heights per texel toward
    direction k (k·45° from +x toward the next row, down the image); ``"ambient_occlusion"``, an
    (H, W) float32 array, the cosine-weighted share of the sky each texel sees (1 open);
    ``"bent_normals"``, an (H, W, 4) array encoded as ``normal_map`` encodes normals (green per
    ``y_convention``), the mean open direction.

    ``progress``: a function called ``progress(done, total)`` on the calling thread as rows of
    the horizon map are made (the long part: minutes for 8192² heights).
    """
    return _bumpmap.horizon_maps(heights, options)


def roughness_map(heights, **options):
    """The roughness map GGX shaders read in place of Toksvig's length factor, as
    ``bumpmap normalmap IN --mips --roughness-out R`` writes it: each texel the surface's
    ``roughness`` made rougher by the spread of the normals it averages (Filament's prefilter).

    heights: as for ``normal_map``. Returns a list of (H, W, 4) uint8 arrays, level 0 first,
    down to 1x1, in the channels ``roughness_layout`` names.
    """
    return _bumpmap.roughness_map(heights, options)


def lean_moments(heights, **options):
    """LEAN mapping's moments (Olano & Baker 2010) of the 8-bit normal map, as
    ``bumpmap normalmap IN --lean-out L.ktx2`` writes them, what ``specular_filter="lean"`` draws.

    heights: as for ``normal_map``. Returns ``(moments, mxy_j)``, each a list of (H, W, 4)
    float32 arrays, level 0 first: ``moments`` holds (Bx, By, Mxx, Myy) and ``mxy_j`` holds
    (Mxy, J, 0, 0), with B = (Nx/Nz, Ny/Nz), M = (Bx², BxBy, By²), J = 1/Nz³, each level the
    mean over the level-0 texels it covers (the two files' channels).
    """
    return _bumpmap.lean_moments(heights, options)


def read_height_field(path, **options):
    """A height field from an image file (PNG, TGA, BMP, JPEG, TIFF, PNM at 8 or 16 bits;
    OpenEXR in float) or a preset (``"bricks"``, ``"pinwheel"``, ``"dimples"``,
    ``"noise:SEED"``, each optionally ``@SIZE``), read as the command line reads it.

    Returns an (H, W) array with the samples as stored: uint8, uint16 or float32, row 0 first.
    """
    return _bumpmap.read_height_field(path, options)


def write_texture(path, levels, **options):
    """Writes a normal map, or a chain of levels, as ``bumpmap normalmap -o PATH`` writes one.

    path: by its extension: ``.png`` (level 0, and ``NAME.mip1.png``, ... beside it), ``.dds``
    or ``.ktx2`` (every level in one file). levels: one (H, W, 4) array or a list of them, level
    0 first, each half the size of the one before; uint8, or uint16 for 16-bit PNG, DDS and
    KTX2. ``format="bc5"`` or ``"bc7"`` compresses (``.dds``/``.ktx2`` only, uint8 only).
    All files are written or none. Returns the paths written.
    """
    return _bumpmap.write_texture(path, levels, options)


def read_texture(path):
    """A texture file read back, the inverse of ``write_texture``: a dict of

    - ``levels``: every level, level 0 first, each an (H, W, 4) array of uint8 (uint16 for a
      16-bit file): a DDS's or KTX2's own levels (BC5 and BC7 decoded; BC5's Z rebuilt as
      ``sqrt(1 - x² - y²)``), a PNG's with the ``NAME.mip1.png``, ... files beside it;
    - ``format``: how the file stores them (``"rgba8"``, ``"rgba16"``, ``"bc5"``, ``"bc7"``);
    - ``y_convention``: ``"opengl"`` or ``"directx"``, as level 0's texels show it (the curl
      test of ``inspect``), or ``None`` where it cannot be told.
    """
    return _bumpmap.read_texture(path)


def tangents(positions, normals, uvs, indices, **options):
    """Tangent frames for a mesh, as ``bumpmap tangents`` makes them.

    positions: (N, 3) float32; normals: (N, 3) float32 (normalized on the way in, as a glTF
    reader does), or None to have them made from the faces; uvs: (N, 2) float32 in glTF's convention (v = 0 at the image's top; from Blender or an
    OBJ, pass ``1 - v``); indices: (T, 3) or (3T,) uint32, counter-clockwise seen from the front.

    Returns a dict: ``positions``, ``normals``, ``uvs`` and ``tangents`` ((N', 4) float32, xyz the
    unit tangent along +u, w = +1 or -1 as glTF's TANGENT has it: bitangent = w * cross(N, T)),
    ``indices`` ((T, 3) uint32) for the mesh out, where a vertex may have been split in two
    (``mode="ours"`` splits where tangents differ by more than ``split_angle`` degrees), exactly
    as the command's glTF file holds them (unit normals and tangents, a zero one rebuilt), and
    ``report``: how many triangles were degenerate or mirrored, how many vertices were split and
    how many normals and tangents had to be rebuilt.
    """
    return _bumpmap.tangents(positions, normals, uvs, indices, options)


def render(**options):
    """Renders a bump-mapped scene, as ``bumpmap render`` does.

    Any technique of the catalogue (``techniques()``) on the emulated GeForce pipeline
    (``backend="cpu"``, the default), the GPU (``"gpu"``) or whichever exists (``"auto"``).
    ``size`` is the square side in pixels (or give ``width`` and ``height``). Vectors are
    tuples (or lists or arrays) of numbers: ``eye=(0, -6, 3)``, ``torus_radii=(2, 0.7)``.
    ``light`` takes one light or a list of them, each a position ``(x, y, z)`` (white), a dict
    ``{"position": (x, y, z), "color": (r, g, b)}`` or ``{"direction": (x, y, z)}`` (toward a
    light at infinity; the colour optional), or the command line's notation
    ``"[dir:]X,Y,Z[@R,G,B]"``: ``light=[(4, 0, 3), {"direction": (-1, 0, 1), "color": (0.3, 0.3,
    0.6)}]``. ``attenuation`` is ``(C, L, Q)`` or ``"exp:D"``, ``"exp2:D"``. The keywords are read
    straight into the library's typed options (``bumpmap::options::SceneOptions``): a value of
    the wrong type is a ``TypeError`` naming the keyword, one out of range a ``ValueError``.

    Returns an (H, W, 4) uint8 array, row 0 the image's top; alpha is 255 (the framebuffer's
    alpha holds a self-shadowing term, not coverage, and the command line's PNG leaves it out).

    ``progress``: a function called ``progress(done, total)`` on the calling thread as the
    steps finish (at most every 50 ms): the rows of the horizon map where the technique reads one
    (``horizon``, a march's horizon shadow or occlusion), then the reference's tiles; and once at
    the end with ``done == total`` (``1, 1`` for a technique that counts no steps). An exception
    it raises, or Ctrl-C, stops the render at its next step.
    """
    return _bumpmap.render(_objects_as_options(options))


def compare(output=None, **options):
    """Renders every technique on one scene and measures each against the ground-truth
    reference, as ``bumpmap compare`` does (minutes at the default size; try ``size=64,
    spp=4``).

    Returns the results as a dict (what ``results.json`` holds: each technique's RMSE, PSNR,
    bias, FLIP and SSIM against the reference and, for the techniques that take heights as
    geometry, against the displaced reference; the skipped ones with their reason; and the
    studies ``studies`` asks for: golf ball, specular filtering, embossing, Peercy's figures, and
    heights as geometry on a wall at grazing angles). With ``output`` (a folder), also writes the report there: images, FLIP heat
    maps, plots, ``results.json`` and ``report.html``, all files or none.

    ``progress``: a function called ``progress(done, total)`` on the calling thread as each
    reference, technique and study is done, and once at the end with ``done == total``; an
    exception it raises stops the comparison (nothing is written).
    """
    return _bumpmap.compare(output, options)


def techniques():
    """The catalogue: a list of ``(name, description, needs)``, in the order ``compare`` draws
    them; ``needs`` lists what a technique requires of the scene (a built-in surface, a height
    field, one light)."""
    return _bumpmap.techniques()


def inspect(source):
    """What a normal map is, as ``bumpmap inspect --json`` says it.

    source: a file (PNG 8/16-bit, TGA, TIFF, JPEG, OpenEXR, DDS or KTX2 with their levels, BC5
    and BC7 included), or an (H, W, 3) or (H, W, 4) numpy array of uint8 or uint16 (unorm) or
    float32 (signed where any of RGB is below -0.01, else 0..1), row 0 the image's top.

    Returns a dict: ``"normal_map"`` (bool) and ``"kind"``; ``"convention"`` with its
    ``"verdict"`` (``"opengl"``, ``"directx"`` or ``"undecidable"``, by the curl test: a map
    made from heights has no curl when green is read the way it was written), ``"confidence"``,
    ``"reason"`` where undecidable and ``"made_with"`` (the kernel its slopes fit best);
    ``"texels"`` (unit lengths, texels facing away, gray texels); ``"mips"`` (how the smaller
    levels were made: ``"box"``, ``"length-in-alpha"``, ``"renormalized"``, ``"smooth"`` or
    ``"other"``, and what renormalizing costs); ``"seam"`` (whether the map and its heights
    tile); ``"compression_degrees"`` (what BC5/BC7 added, where it can be estimated); and
    ``"findings"``, what needs fixing (``bumpmap inspect --strict`` exits 1 on any).
    """
    return _bumpmap.inspect(source)


def bake(high, low, **options):
    """A high-poly mesh's detail baked into a normal map over a low-poly mesh's UV layout, as
    ``bumpmap bake HIGH LOW`` bakes it: each texel's rays start in front of LOW (``extrude``,
    the cage) and go inward as far as ``max_distance`` behind it, along LOW's averaged normals
    (``ray="explicit"``: its own); the first hit from the cage inward wins, and HIGH's normal
    there is stored in LOW's tangent frame, inverted exactly for ``decode``.

    high, low: mesh files (.obj, .gltf, .glb) or ``Mesh`` objects, in any mix; LOW needs
    texture coordinates (HIGH's are not read: zeros will do for a ``Mesh``). LOW's own tangents
    are used where it has them, else ones made in ``tangents``' mode; normals are made from
    the faces where a mesh has none.

    Returns a dict: ``levels`` (the normal map, level 0 first, as ``mip_chain`` returns a
    chain), ``object_space`` ((H, W, 3) float32 unit normals), ``displacement`` ((H, W)
    float32, the signed distance from LOW to HIGH along the ray), ``curvature`` ((H, W) float32,
    HIGH's mean curvature at the hit in 1 / the meshes' units, positive where convex), with
    ``ao_rays`` above 0
    ``occlusion`` ((H, W) float32, HIGH's ambient occlusion, 1 unoccluded), ``hit`` and ``covered``
    ((H, W) bool: texels whose rays met HIGH, and texels of LOW's layout). Most rays meeting
    nothing raises, never a flat map.

    ``progress``: a function called ``progress(done, total)`` as rows of texels are baked.
    """
    return _bumpmap.bake(high, low, options)


def height_from_normals(normals, **options):
    """Heights from a normal map, as ``bumpmap normalmap``'s inverse: the least-squares surface
    whose slopes the map holds, as ``bumpmap height`` makes it.

    normals: an (H, W, 3) or (H, W, 4) numpy array as ``inspect`` takes it. The Y convention
    and the kernel come from the map (the curl test, the least-squares fit) unless given; the
    method is ``fft`` where the map and its heights tile, else ``dct``.

    Returns an (H, W) float32 array: the heights mapped onto [0, 1] (lowest 0, highest 1; all 0
    for a flat map), or with ``raw=True`` in texels divided by ``scale``, mean zero.
    """
    return _bumpmap.height_from_normals(normals, options)


def blend_normals(base, detail, **options):
    """A detail normal map laid over a base one, as ``bumpmap blend BASE DETAIL`` lays it.

    base, detail: (H, W, 3) or (H, W, 4) numpy arrays as ``inspect`` takes them (uint8, uint16
    or float32), or ``NormalMap`` objects (their level 0 and Y convention). The detail repeats
    ``detail_repeat`` times across the base (bilinear, wrapping), its slopes times
    ``detail_strength``, laid over the base by ``method``: ``"rnm"`` is exact for a detail
    draped over the base's bumps, ``"partial-derivative"`` for heights that add.

    Returns the result's levels, level 0 first (every level with ``mips=True``), at the base's
    size: uint8, or uint16 where either input is 16-bit or float (or as ``bits`` says). A detail
    of the other Y convention (``detail_y_convention``) is flipped to the base's; each such
    conversion is said as a ``BumpmapWarning``.
    """
    if isinstance(base, NormalMap):
        options.setdefault("y_convention", base.y_convention)
        base = base.levels[0]
    if isinstance(detail, NormalMap):
        options.setdefault("detail_y_convention", detail.y_convention)
        detail = detail.levels[0]
    return _bumpmap.blend_normals(base, detail, options)


Scene = _bumpmap.Scene


class NormalMap:
    """A normal map and its smaller levels as arrays, with the Y convention its green follows:
    what ``mip_chain`` makes, ``read_texture`` reads and ``render`` draws, kept together.

    levels: one (H, W, 4) array or a list of them, level 0 first (uint8, or uint16 for a 16-bit
    map), each half the size of the one before; y_convention: ``"opengl"`` (green up: glTF,
    Blender, and what bumpmap makes) or ``"directx"``. ``render(normal_map=nm)`` draws it as
    ``render(normal_map=nm.levels, y_convention=nm.y_convention)`` (a ``y_convention`` given
    there wins); a single level gets its smaller levels made with the length in alpha, as a
    file with one level does.
    """

    def __init__(self, levels, y_convention="opengl"):
        levels = [levels] if getattr(levels, "ndim", None) == 3 else list(levels)
        if not levels:
            raise ValueError("NormalMap(): levels is empty: give level 0 at least")
        if y_convention not in ("opengl", "directx"):
            raise ValueError(f"NormalMap(): y_convention must be 'opengl' or 'directx', not {y_convention!r}")
        self.levels, self.y_convention = levels, y_convention

    @classmethod
    def from_heights(cls, heights, *, mips=True, **options):
        """Made from heights by ``mip_chain(heights, **options)`` (every level, the length in
        alpha), or ``normal_map`` with ``mips=False`` (level 0 only)."""
        levels = mip_chain(heights, **options) if mips else [normal_map(heights, **options)]
        return cls(levels, options.get("y_convention", "opengl"))

    @classmethod
    def read(cls, path, y_convention=None):
        """A texture file's levels (``read_texture``), their Y convention as level 0's texels show
        it, or ``y_convention`` where given (also where the texels cannot tell: then it is needed,
        and its absence a ``ValueError``)."""
        texture = read_texture(path)
        told = y_convention or texture["y_convention"]
        if told is None:
            raise ValueError(f"NormalMap.read(): {path}: its texels do not tell OpenGL from DirectX; "
                             "give y_convention='opengl' or 'directx'")
        return cls(texture["levels"], told)

    def write(self, path, *, format="rgba8"):
        """``write_texture(path, self.levels, format=format)``; returns the paths written."""
        return write_texture(path, self.levels, format=format)

    def inspect(self):
        """``inspect`` of level 0."""
        return inspect(self.levels[0])

    def heights(self, **options):
        """``height_from_normals`` of level 0, read with this map's Y convention unless
        ``y_convention`` is given."""
        options.setdefault("y_convention", self.y_convention)
        return height_from_normals(self.levels[0], **options)

    @property
    def size(self):
        """Level 0's (width, height)."""
        return self.levels[0].shape[1], self.levels[0].shape[0]

    def __len__(self):
        return len(self.levels)

    def __repr__(self):
        w, h = self.size
        return f"NormalMap({w}x{h}, {len(self.levels)} levels, {self.levels[0].dtype}, {self.y_convention})"


def _objects_as_options(options):
    """``render``'s options with a ``NormalMap`` given as its levels and Y convention."""
    given = options.get("normal_map")
    if isinstance(given, NormalMap):
        options = {**options, "normal_map": given.levels}
        options.setdefault("y_convention", given.y_convention)
    return options


class Mesh:
    """A triangle mesh as arrays, drawn as a scene: ``render(scene=mesh)`` or
    ``renderer.prepare(scene=mesh)`` draws it as ``scene="mesh:FILE"`` draws a file without a
    material (the scene's bumps, decal and material options apply, as for an OBJ), in its own
    units, the camera framing it.

    positions: (N, 3) float32; uvs: (N, 2) float32, as glTF stores them; indices: (T, 3) or
    (3T,) uint32, counter-clockwise in front; normals: (N, 3) float32, or None to make them from
    the faces; tangents: (N, 4) float32 with glTF's ``w``, or None to make them (as
    ``tangents(mode="ours")`` does). The arrays are kept as given and checked when drawn:
    a wrong dtype or shape is a ``TypeError`` or ``ValueError``, an index past the vertices or a
    non-finite value a ``ValueError``.
    """

    def __init__(self, positions, uvs, indices, normals=None, tangents=None):
        self.positions, self.uvs, self.indices = positions, uvs, indices
        self.normals, self.tangents = normals, tangents

    @classmethod
    def from_tangents(cls, made):
        """The mesh ``tangents(...)`` returned (its vertices split where the frames differ)."""
        return cls(made["positions"], made["uvs"], made["indices"], made["normals"], made["tangents"])

    def with_tangents(self, **options):
        """This mesh with tangent frames made by ``tangents(**options)`` (``mode="mikktspace"``
        for Blender's and the glTF sample viewer's)."""
        return Mesh.from_tangents(tangents(self.positions, self.normals, self.uvs, self.indices, **options))

    def __repr__(self):
        n = len(self.positions)
        t = len(self.indices) if getattr(self.indices, "ndim", 1) == 2 else len(self.indices) // 3
        return f"Mesh({n} vertices, {t} triangles{'' if self.tangents is None else ', with tangents'})"


class Renderer:
    """A backend opened once (``backend``: ``"cpu"``, ``"gpu"`` or ``"auto"``): the GPU's adapter,
    device and pipelines, and every backend's texture caches, are kept between frames.

    ``prepare(**options)`` sets a scene up once from ``render``'s options (arrays or files) and
    returns a ``Scene``, whose ``render(light=(x, y, z), eye=(x, y, z))`` draws a frame, with
    the first light or the camera moved there (world space), as an (H, W, 4) uint8 array::

        renderer = bumpmap.Renderer("gpu")
        scene = renderer.prepare(scene="sphere", technique="pom", size=512)
        frames = [scene.render(light=(4 * math.cos(a), 4 * math.sin(a), 3)) for a in angles]

    A scene keeps its renderer. ``close()`` (or leaving a ``with`` block) frees the device;
    drawing afterwards raises ``RuntimeError``.
    """

    def __init__(self, backend="cpu"):
        self._native = _bumpmap.Renderer(backend)

    def prepare(self, **options):
        """A ``Scene`` set up once from ``render``'s options (but ``backend``: the renderer's)."""
        return self._native.prepare(_objects_as_options(options))

    def render(self, **options):
        """One frame of ``prepare(**options)``: ``render(**options)`` on this renderer."""
        return self._native.prepare(_objects_as_options(options)).render()

    def describe(self):
        """What it draws on, in words."""
        return self._native.describe()

    def close(self):
        """Frees the device and caches; drawing afterwards raises ``RuntimeError``."""
        self._native.close()

    @property
    def closed(self):
        """Whether ``close()`` was called."""
        return self._native.closed

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _default(text):
    """A default as the command line writes it, as the Python value a caller would pass: a
    number, a tuple of numbers (``"2,0.7"`` is ``(2.0, 0.7)``) or a word."""
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    parts = text.split(",")
    if len(parts) > 1 and all(_is_number(p) for p in parts):
        return tuple(float(p) for p in parts)
    return text


# Keywords of the package's own beside the command line's options.
_OWN_KEYWORDS = {"render": ["progress"], "compare": ["progress"], "bake": ["progress"], "horizon_maps": ["progress"]}


def _signature(function, leading):
    """``function``'s real signature: its leading parameters (kept as the wrapper has them),
    then every option as a keyword-only parameter with the command line's default (a flag's is
    False; an option with no default, None), then the package's own keywords (default None)."""
    own = _inspect.signature(function)
    params = [p for p in own.parameters.values() if p.kind is not _inspect.Parameter.VAR_KEYWORD]
    params = params[:leading]
    for name, default, _help, _choices, flag in _bumpmap.options(function.__name__):
        value = False if flag else None if default is None else _default(default)
        params.append(_inspect.Parameter(name, _inspect.Parameter.KEYWORD_ONLY, default=value))
    for name in _OWN_KEYWORDS.get(function.__name__, []):
        params.append(_inspect.Parameter(name, _inspect.Parameter.KEYWORD_ONLY, default=None))
    return _inspect.Signature(params)


for _f, _leading in ((normal_map, 1), (mip_chain, 1), (height_mips, 1), (write_heights, 2), (horizon_maps, 1),
                     (roughness_map, 1), (lean_moments, 1), (read_height_field, 1),
                     (write_texture, 2), (tangents, 4), (render, 0), (compare, 1), (height_from_normals, 1),
                     (bake, 2), (blend_normals, 2)):
    _f.__doc__ = _inspect.cleandoc(_f.__doc__ or "") + _options_doc(_f.__name__)
    _f.__signature__ = _signature(_f, _leading)
del _f, _leading
Renderer.prepare.__signature__ = _inspect.Signature(
    [_inspect.Parameter("self", _inspect.Parameter.POSITIONAL_OR_KEYWORD)]
    + [p for p in render.__signature__.parameters.values() if p.name not in ("backend", "progress")]
)
