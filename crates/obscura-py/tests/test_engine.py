"""The engine path (EngineInput): depth in any convention, normals, projection in, AO out; held
to the Rust test's bound (crates/obscura/tests/it/engine_input.rs,
every_depth_convention_gives_our_linear_depth_and_ao: mean AO difference from our own pipeline
< 2e-3 on the stairs close-up at 96x64, guard band 16)."""

import numpy as np
import pytest

import obscura

W, H, BAND = 96, 64, 16


def ndc_depth(g, projection, far):
    """NDC z of the G-buffer's linear depth under `projection` (background: `far`)."""
    depth = g["depth"]
    fh, fw = depth.shape
    p = g["projection"]
    tan_x, tan_y = 1.0 / p[0, 0], 1.0 / p[1, 1]
    x = ((np.arange(fw) + 0.5) / fw * 2 - 1)[None, :] * tan_x * depth
    y = (1 - (np.arange(fh) + 0.5) / fh * 2)[:, None] * tan_y * depth
    view = np.stack([x, y, -depth, np.ones_like(depth)], axis=-1)
    clip = view @ np.asarray(projection, dtype=np.float64).T
    # Sky pixels (depth 0) divide by w = 0; np.where replaces them with `far`.
    with np.errstate(divide="ignore", invalid="ignore"):
        z = clip[..., 2] / clip[..., 3]
    return np.where(depth > 0, z, far).astype(np.float32)


def standard_z(g, near, far):
    """glam's perspective_rh (DirectX-style: z in [0, 1], 0 at near) of the same frustum."""
    p = g["projection"]
    r = far / (near - far)
    return np.array(
        [[p[0, 0], 0, 0, 0], [0, p[1, 1], 0, 0], [0, 0, r, r * near], [0, 0, -1, 0]],
        dtype=np.float32,
    )


@pytest.fixture(scope="module")
def frame(stairs):
    g = obscura.gbuffer(stairs, width=W, height=H, guard_band=BAND)
    ours = obscura.render(stairs, "vao", width=W, height=H, guard_band=BAND)
    return g, ours


def test_gbuffer_arrays(frame):
    g, _ = frame
    assert g["depth"].shape == (H + 2 * BAND, W + 2 * BAND) and g["depth"].dtype == np.float32
    assert g["normals"].shape == (H + 2 * BAND, W + 2 * BAND, 3)
    assert g["depth"].flags["C_CONTIGUOUS"] and g["normals"].flags["C_CONTIGUOUS"]
    covered = g["depth"] > 0
    assert covered.any() and not covered.all()
    lengths = np.linalg.norm(g["normals"][covered], axis=-1)
    assert np.allclose(lengths, 1, atol=1e-2)


@pytest.mark.parametrize("convention", ["reversed-Z, infinite far", "standard Z, far 100"])
def test_engine_path_gives_our_pipelines_ao(frame, convention):
    g, ours = frame
    if convention.startswith("reversed"):
        projection, far = g["projection"], 0.0
    else:
        projection, far = standard_z(g, 0.05, 100.0), 1.0
    depth = ndc_depth(g, projection, far)
    ao = obscura.engine_ao(depth, projection, g["normals"], technique="vao", guard_band=BAND)
    assert ao.dtype == np.float32 and ao.shape == (H, W) and ao.flags["C_CONTIGUOUS"]
    mean = np.abs(ao - ours).mean()
    assert mean < 2e-3, f"{convention}: AO differs from our pipeline's by {mean} on average"


def test_world_normals_and_reconstructed_normals(frame):
    g, ours = frame
    view = g["view_matrix"]
    # View-space normals back to world space: the inverse of the view matrix's rotation.
    world = g["normals"] @ view[:3, :3]
    depth = ndc_depth(g, g["projection"], 0.0)
    with_world = obscura.engine_ao(
        depth, g["projection"], world, normal_space="world", view_matrix=view, guard_band=BAND
    )
    assert np.abs(with_world - ours).mean() < 2e-3
    # Without normals they are reconstructed from the depth: close, not equal.
    rebuilt = obscura.engine_ao(depth, g["projection"], guard_band=BAND)
    assert np.abs(rebuilt - ours).mean() < 0.05


def test_engine_path_refuses_bad_arrays(frame):
    g, _ = frame
    depth = ndc_depth(g, g["projection"], 0.0)
    with pytest.raises(obscura.InputError, match="normals"):
        obscura.engine_ao(depth, g["projection"], g["normals"][:-1], guard_band=BAND)
    with pytest.raises(obscura.InputError, match="view_matrix"):
        obscura.engine_ao(depth, g["projection"], g["normals"], normal_space="world")
    with pytest.raises(obscura.InputError, match="4x4"):
        obscura.engine_ao(depth, np.eye(3), guard_band=BAND)
