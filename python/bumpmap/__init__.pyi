# Type stubs for bumpmap. The defaults written here are the command line's; a test
# (tests/test_stubs.py) checks each against the options the native module reports.
from os import PathLike
from pathlib import Path
from typing import Any, Literal, Optional, Sequence, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Path = Union[str, PathLike[str]]
_Kernel = Literal["forward", "central", "sobel3", "sobel5", "prewitt3", "scharr3", "gaussian7"]
_Wrap = Literal["repeat", "clamp", "border"]
_YConvention = Literal["opengl", "directx", "y-up", "y-down"]
_Encoding = Literal["unorm", "kilgard"]
_MipMode = Literal["length-in-alpha", "renormalize"]
_Channel = Literal["luminance", "red", "green", "blue", "alpha"]
_Format = Literal["rgba8", "rgba16", "bc5", "bc7"]
_Backend = Literal["cpu", "gpu", "auto"]
_Vec3 = Union[str, Sequence[float]]
_Heights = Union[npt.NDArray[np.uint8], npt.NDArray[np.uint16], npt.NDArray[np.float32]]
_Levels = Union[npt.NDArray[np.uint8], npt.NDArray[np.uint16]]

def normal_map(
    heights: _Heights,
    *,
    scale: float = 4.0,
    kernel: _Kernel = "forward",
    wrap: _Wrap = "repeat",
    encoding: _Encoding = "unorm",
    y_convention: _YConvention = "opengl",
    bits: Literal[8, 16] = 8,
) -> _Levels: ...
def mip_chain(
    heights: _Heights,
    *,
    scale: float = 4.0,
    kernel: _Kernel = "forward",
    wrap: _Wrap = "repeat",
    encoding: _Encoding = "unorm",
    y_convention: _YConvention = "opengl",
    bits: Literal[8, 16] = 8,
    mip_mode: _MipMode = "length-in-alpha",
) -> list[_Levels]: ...
def height_mips(
    heights: _Heights, *, bits: Literal[8, 16] = 8
) -> tuple[list[npt.NDArray[np.float32]], list[npt.NDArray[np.float32]]]: ...
class HorizonMaps(TypedDict):
    horizons: list[npt.NDArray[np.float32]]
    ambient_occlusion: npt.NDArray[np.float32]
    bent_normals: _Levels

def horizon_maps(
    heights: _Heights,
    *,
    scale: float = 4.0,
    kernel: _Kernel = "forward",
    wrap: _Wrap = "repeat",
    encoding: _Encoding = "unorm",
    y_convention: _YConvention = "opengl",
    bits: Literal[8, 16] = 8,
) -> HorizonMaps: ...
def read_height_field(path: _Path, *, channel: _Channel = "luminance") -> _Heights: ...
def write_texture(path: _Path, levels: Union[_Levels, Sequence[_Levels]], *, format: _Format = "rgba8") -> list[Path]: ...

class Texture(TypedDict):
    levels: list[_Levels]
    format: _Format
    y_convention: Optional[Literal["opengl", "directx"]]

def read_texture(path: _Path) -> Texture: ...

class _TangentReport(TypedDict):
    degenerate_uv: int
    degenerate_geometry: int
    mirrored: int
    vertices_split: int
    normals_computed: bool
    normals_repaired: int
    tangents_repaired: int

class TangentMesh(TypedDict):
    positions: npt.NDArray[np.float32]
    normals: npt.NDArray[np.float32]
    uvs: npt.NDArray[np.float32]
    tangents: npt.NDArray[np.float32]
    indices: npt.NDArray[np.uint32]
    report: _TangentReport

def tangents(
    positions: npt.NDArray[np.float32],
    normals: Optional[npt.NDArray[np.float32]],
    uvs: npt.NDArray[np.float32],
    indices: npt.NDArray[np.uint32],
    *,
    mode: Literal["ours", "mikktspace"] = "ours",
    split_angle: float = 60.0,
) -> TangentMesh: ...
def render(
    *,
    scene: str = "torus",
    technique: str = "kilgard",
    backend: _Backend = "cpu",
    size: int = 512,
    width: Optional[int] = None,
    height: Optional[int] = None,
    height_field: Optional[str] = None,
    normal_map: Optional[_Path] = None,
    rebuild_mips: bool = False,
    bump_scale: Optional[float] = None,
    decal: Optional[str] = None,
    eye: Optional[_Vec3] = None,
    target: Optional[_Vec3] = None,
    up: Optional[_Vec3] = None,
    fov: float = 45.0,
    light: Union[None, str, Sequence[float], Sequence[Union[str, Sequence[float]]]] = None,
    ambient: float = 0.2,
    diffuse: float = 0.8,
    specular: float = 1.0,
    shininess: float = 8.0,
    spp: int = 64,
    filter: str = "trilinear",
    depth: Optional[float] = None,
    height_map: Optional[_Path] = None,
    layers: int = 32,
    parallax_shadow: Literal["off", "hard", "soft", "horizon"] = "off",
    silhouettes: bool = False,
    write_depth: bool = False,
    **options: Any,
) -> npt.NDArray[np.uint8]: ...
def compare(
    output: Optional[_Path] = None,
    *,
    scene: str = "torus",
    height_field: str = "bricks",
    bump_scale: float = 4.0,
    size: int = 256,
    spp: int = 64,
    backend: _Backend = "cpu",
    techniques: Optional[Sequence[str]] = None,
    studies: Union[str, Sequence[str]] = "all",
) -> dict[str, Any]: ...
def techniques() -> list[tuple[str, str, list[str]]]: ...

_Normals = Union[npt.NDArray[np.uint8], npt.NDArray[np.uint16], npt.NDArray[np.float32]]

def inspect(source: Union[_Path, _Normals]) -> dict[str, Any]: ...
def height_from_normals(
    normals: _Normals,
    *,
    method: Literal["auto", "fft", "dct", "kernel"] = "auto",
    kernel: Union[Literal["auto", "spectral"], _Kernel] = "auto",
    scale: float = 1.0,
    y_convention: Literal["auto", "opengl", "directx", "y-up", "y-down"] = "auto",
    raw: bool = False,
) -> npt.NDArray[np.float32]: ...
