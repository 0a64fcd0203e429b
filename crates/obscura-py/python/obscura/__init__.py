"""obscura: screen-space ambient occlusion that keeps the geometry a depth buffer hides.

The Python face of the obscura library (docs/PYTHON.md). Every call goes through the same
library code as the ``obscura`` command line, so the same scene, view, row and settings give the
same bits. AO images are float32 numpy arrays of shape (height, width), C-contiguous, rows top to
bottom, 1 = unoccluded.

    import obscura
    scene = obscura.Scene("stairs")
    ao = obscura.render(scene, "gtao", {"gtao": {"radius": 0.5}}, width=320, height=180)
"""

import json as _json
import os as _os
from typing import Any, Dict, Optional, Sequence, Union

import numpy as _np

from ._native import (  # noqa: F401  (re-exported)
    CameraError,
    Camera,
    DatasetError,
    Device,
    GpuError,
    InputError,
    ObscuraError,
    OutputError,
    Scene,
    SceneError,
    SettingsError,
    __version__,
    builtin_scenes,
    default as default_device,
    gbuffer,
    read_ao,
    reference,
    render,
    techniques,
)
from . import _native
from . import dataset  # noqa: F401  (obscura.dataset.run)

__all__ = [
    "Camera",
    "CameraError",
    "DatasetError",
    "Device",
    "GpuError",
    "InputError",
    "ObscuraError",
    "OutputError",
    "Scene",
    "SceneError",
    "SettingsError",
    "builtin_scenes",
    "compare",
    "default_device",
    "engine_ao",
    "gbuffer",
    "read_ao",
    "reference",
    "render",
    "settings",
    "techniques",
]

SettingsArg = Union[None, Dict[str, Any], str, "_os.PathLike[str]"]


def settings(
    technique: Optional[str] = None,
    settings: SettingsArg = None,
    *,
    preset: Optional[str] = None,
    units: Optional[str] = None,
) -> Dict[str, Any]:
    """The full settings ``render`` would run with, as a dict (every field; α written out).

    Arguments as for ``render``. Raises ``SettingsError`` (with ``.path``) where ``render`` would.
    """
    return _json.loads(_native.settings_json(technique, settings, preset=preset, units=units))


def compare(scene: Scene, techniques: Sequence[str], **kwargs: Any) -> Dict[str, Any]:
    """Compare ``techniques`` with the ray-traced reference of one view.

    As ``obscura compare --timing-frames 0``: returns its report (``report.json``) as a dict, whose
    ``results`` hold each technique's ``mse``, ``mae``, ``psnr``, ``ssim``, ``halo_bright`` and
    ``halo_dark`` (a non-finite metric is None) and the settings it ran with. Keyword arguments:
    ``reference_model`` (``"vao"``, ``"vao-mean"``, ``"hemisphere"``), ``camera``, ``width``,
    ``height``, ``guard_band``, ``settings``, ``preset``, ``units``, ``spp``, ``falloff``,
    ``seed``, ``tracer``, ``cache``, ``device``, as for ``render`` and ``reference``.
    """
    if isinstance(techniques, str):
        techniques = [techniques]
    return _json.loads(_native.compare_json(scene, list(techniques), **kwargs))


def engine_ao(
    depth: Any,
    projection: Any,
    normals: Any = None,
    **kwargs: Any,
) -> _np.ndarray:
    """AO from an engine's frame as arrays (the library's ``EngineInput``).

    ``depth``: NDC z in [0, 1] per framebuffer pixel, shape (height + 2·guard_band,
    width + 2·guard_band), any depth convention ``projection`` rasterises with; ``projection``:
    4×4 (``m @ v``); ``normals``: None (reconstructed from depth) or (…, …, 3) in
    ``normal_space`` ``"view"`` or ``"world"`` (then with ``view_matrix``). Arrays of any float
    dtype and layout are converted to C-contiguous float32 first. Other keyword arguments:
    ``technique``, ``settings``, ``guard_band`` (default 0), ``preset``, ``units``, ``device``.
    Returns float32 (height, width).
    """
    depth = _np.ascontiguousarray(depth, dtype=_np.float32)
    projection = _np.asarray(projection, dtype=_np.float32)
    if projection.shape != (4, 4):
        raise InputError(f"projection has shape {projection.shape}: give a 4x4 matrix")
    if depth.ndim != 2:
        raise InputError(f"depth has shape {depth.shape}: give (height, width) of NDC z")
    if normals is not None:
        normals = _np.ascontiguousarray(normals, dtype=_np.float32)
        if normals.ndim != 3 or normals.shape[2] != 3:
            raise InputError(f"normals have shape {normals.shape}: give (height, width, 3)")
    view_matrix = kwargs.pop("view_matrix", None)
    if view_matrix is not None:
        view_matrix = _np.asarray(view_matrix, dtype=_np.float32).tolist()
    return _native.engine_ao(
        depth, projection.tolist(), normals, view_matrix=view_matrix, **kwargs
    )
