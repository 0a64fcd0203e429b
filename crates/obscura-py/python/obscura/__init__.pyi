"""Type stubs of the obscura package (docs/PYTHON.md). AO images are float32 arrays of shape
(height, width), C-contiguous, rows top to bottom, 1 = unoccluded."""

import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import dataset as dataset

__version__: str

Settings = Union[None, Dict[str, Any], str, "os.PathLike[str]"]
Vec3 = Tuple[float, float, float]
Image = npt.NDArray[np.float32]

class ObscuraError(Exception):
    """Every error obscura raises; the message is the library's (the CLI's, after "error: ")."""

class SettingsError(ObscuraError):
    """Invalid settings; ``path`` is the settings field's path (``"vao.radius"``) or None."""

    path: Optional[str]

class SceneError(ObscuraError):
    """A scene that cannot be loaded or used."""

class CameraError(SceneError):
    """An unknown camera name or a degenerate camera."""

class GpuError(ObscuraError):
    """No adapter, no device, a validation error or an adapter limit."""

class InputError(ObscuraError):
    """An unusable argument: an array's shape, a size, an option, an unreadable image."""

class OutputError(ObscuraError):
    """Writing an output file failed."""

class DatasetError(ObscuraError):
    """A dataset spec's field (named in the message) or a failed dataset run."""

class Device:
    """A GPU device, chosen as ``obscura --adapter/--backend/--gpu-index`` choose one. ``ordinal``: the
    N-th GPU in PCI bus order (as ``nvidia-smi`` and Ray's GPU ids count them)."""

    def __init__(
        self,
        adapter: Optional[str] = None,
        backend: Optional[str] = None,
        ordinal: Optional[int] = None,
    ) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def backend(self) -> str: ...
    @property
    def is_software(self) -> bool: ...

def default_device() -> Device:
    """The module's default device, made on first use (the first adapter, as the CLI picks)."""

class Camera:
    """A pinhole camera in the loaded scene's world coordinates."""

    name: str
    note: Optional[str]
    def __init__(
        self, eye: Vec3, target: Vec3, fov: float = 60.0, up: Optional[Vec3] = None
    ) -> None: ...
    @property
    def eye(self) -> Vec3: ...
    @property
    def target(self) -> Vec3: ...
    @property
    def up(self) -> Vec3: ...
    @property
    def fov(self) -> float: ...
    def view_matrix(self) -> npt.NDArray[np.float32]: ...

class Scene:
    """A built-in scene or a .gltf/.glb/.obj file, loaded as the CLI loads it."""

    def __init__(
        self,
        spec: Union[str, "os.PathLike[str]"],
        *,
        normals: str = "shading",
        sides: str = "authored",
        allow_outside_files: bool = False,
    ) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def cameras(self) -> List[str]: ...
    @property
    def triangle_count(self) -> int: ...
    def camera(
        self,
        name: Optional[str] = None,
        *,
        eye: Optional[Vec3] = None,
        target: Optional[Vec3] = None,
        up: Optional[Vec3] = None,
        fov: Optional[float] = None,
        aspect: float = 16.0 / 9.0,
    ) -> Camera: ...

CameraArg = Union[None, Camera, str]

def builtin_scenes() -> List[str]: ...
def techniques() -> List[str]: ...
def settings(
    technique: Optional[str] = None,
    settings: Settings = None,
    *,
    preset: Optional[str] = None,
    units: Optional[str] = None,
) -> Dict[str, Any]: ...
def render(
    scene: Scene,
    technique: Optional[str] = None,
    settings: Settings = None,
    *,
    camera: CameraArg = None,
    width: int = 640,
    height: int = 360,
    guard_band: Optional[int] = None,
    preset: Optional[str] = None,
    units: Optional[str] = None,
    frames: int = 1,
    device: Optional[Device] = None,
) -> Image: ...
def gbuffer(
    scene: Scene,
    *,
    camera: CameraArg = None,
    width: int = 640,
    height: int = 360,
    guard_band: Optional[int] = None,
    device: Optional[Device] = None,
) -> Dict[str, Any]: ...
def reference(
    scene: Scene,
    model: str = "vao",
    *,
    camera: CameraArg = None,
    width: int = 640,
    height: int = 360,
    guard_band: Optional[int] = None,
    spp: Optional[int] = None,
    falloff: bool = False,
    seed: Optional[int] = None,
    settings: Settings = None,
    preset: Optional[str] = None,
    units: Optional[str] = None,
    tracer: str = "auto",
    cache: bool = False,
    device: Optional[Device] = None,
) -> Image: ...
def compare(
    scene: Scene,
    techniques: Sequence[str],
    *,
    reference_model: str = "vao",
    camera: CameraArg = None,
    width: int = 640,
    height: int = 360,
    guard_band: Optional[int] = None,
    settings: Settings = None,
    preset: Optional[str] = None,
    units: Optional[str] = None,
    spp: Optional[int] = None,
    falloff: bool = False,
    seed: Optional[int] = None,
    tracer: str = "auto",
    cache: bool = False,
    device: Optional[Device] = None,
) -> Dict[str, Any]: ...
def engine_ao(
    depth: npt.ArrayLike,
    projection: npt.ArrayLike,
    normals: Optional[npt.ArrayLike] = None,
    *,
    normal_space: str = "view",
    view_matrix: Optional[npt.ArrayLike] = None,
    technique: Optional[str] = None,
    settings: Settings = None,
    guard_band: int = 0,
    preset: Optional[str] = None,
    units: Optional[str] = None,
    device: Optional[Device] = None,
) -> Image: ...
def read_ao(path: Union[str, "os.PathLike[str]"]) -> Image: ...
