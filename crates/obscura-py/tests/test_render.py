"""render, reference and compare give the CLI's results bit for bit, as float32 (height, width)
C-contiguous arrays."""

import json

import numpy as np
import pytest

import obscura
from conftest import same_bits

W, H = 96, 64


def test_render_returns_float32_rows_top_to_bottom_c_contiguous(stairs):
    ao = obscura.render(stairs, "vao", width=W, height=H)
    assert ao.dtype == np.float32
    assert ao.shape == (H, W)
    # Row-major and writable (numpy holds the buffer through a base object, so OWNDATA is false).
    assert ao.flags["C_CONTIGUOUS"] and ao.flags["WRITEABLE"]
    assert np.isfinite(ao).all() and ao.min() >= 0.0 and ao.max() <= 1.0
    # The stairs' close-up is occluded somewhere and open somewhere.
    assert ao.min() < 0.5 and ao.max() == 1.0


@pytest.mark.parametrize(
    "technique, toml, fields, extra",
    [
        ("vao", "", None, []),
        ("gtao", "[gtao]\nradius = 0.4\nslices = 3\n", {"gtao": {"radius": 0.4, "slices": 3}}, []),
        ("sd-vao", "[blur]\nenabled = false\n", {"blur.enabled": False}, ["--preset", "high"]),
    ],
)
def test_render_equals_the_cli_bit_for_bit(cli, stairs, tmp_path, technique, toml, fields, extra):
    out = tmp_path / "cli.exr"
    args = ["render", "--scene", "stairs", "--size", f"{W}x{H}", "--technique", technique]
    if toml:
        settings = tmp_path / "s.toml"
        settings.write_text(toml)
        args += ["--settings", settings]
    run = cli(*args, *extra, "--out", out)
    assert run.returncode == 0, run.stderr
    expected = obscura.read_ao(out)
    preset = extra[1] if extra else None
    from_dict = obscura.render(stairs, technique, fields, width=W, height=H, preset=preset)
    assert same_bits(from_dict, expected)
    if toml:
        from_file = obscura.render(
            stairs, technique, str(tmp_path / "s.toml"), width=W, height=H, preset=preset
        )
        assert same_bits(from_file, expected)


def test_named_camera_units_and_guard_band_as_the_cli(cli, tmp_path):
    scene = obscura.Scene("colonnade", normals="face", sides="double")
    out = tmp_path / "cli.exr"
    run = cli(
        "render", "--scene", "colonnade", "--camera", "overview", "--normals", "face",
        "--double-sided", "--units", "cm", "--guard-band", "8", "--size", "80x48",
        "--technique", "hbao", "--out", out,
    )
    assert run.returncode == 0, run.stderr
    ao = obscura.render(
        scene, "hbao", camera="overview", units="cm", guard_band=8, width=80, height=48
    )
    assert same_bits(ao, obscura.read_ao(out))
    # And the units did change something: metres give another image.
    assert not same_bits(
        ao, obscura.render(scene, "hbao", camera="overview", guard_band=8, width=80, height=48)
    )


def test_eye_target_camera_as_the_cli(cli, stairs, tmp_path):
    out = tmp_path / "cli.exr"
    run = cli(
        "render", "--scene", "stairs", "--eye", "1.5,1.2,3", "--target", "0,0.5,0",
        "--fov", "50", "--size", f"{W}x{H}", "--out", out,
    )
    assert run.returncode == 0, run.stderr
    camera = stairs.camera(eye=(1.5, 1.2, 3), target=(0, 0.5, 0), fov=50)
    assert camera.name == "custom" and camera.fov == 50
    ao = obscura.render(stairs, "vao", camera=camera, width=W, height=H)
    assert same_bits(ao, obscura.read_ao(out))


def test_reference_equals_the_cli(cli, stairs, tmp_path):
    out = tmp_path / "ref.exr"
    run = cli(
        "reference", "--scene", "stairs", "--size", "64x40", "--model", "vao", "--no-cache",
        "--out", out,
    )
    assert run.returncode == 0, run.stderr
    ref = obscura.reference(stairs, "vao", width=64, height=40)
    assert ref.dtype == np.float32 and ref.shape == (40, 64) and ref.flags["C_CONTIGUOUS"]
    assert same_bits(ref, obscura.read_ao(out))


def test_reference_cache_is_the_clis(cli, stairs, tmp_path, monkeypatch):
    # cache=True fills the CLI's reference cache and the CLI reuses it (same key, same bits);
    # without it nothing is written there.
    monkeypatch.setenv("OBSCURA_CACHE_DIR", str(tmp_path / "cache"))
    args = dict(width=48, height=32, spp=8)
    obscura.reference(stairs, "hemisphere", **args)
    assert not (tmp_path / "cache").exists()
    ref = obscura.reference(stairs, "hemisphere", cache=True, **args)
    assert len(list((tmp_path / "cache").iterdir())) >= 1
    out = tmp_path / "ref.exr"
    run = cli(
        "reference", "--scene", "stairs", "--size", "48x32", "--model", "hemisphere",
        "--spp", "8", "--out", out,
    )
    assert run.returncode == 0, run.stderr
    assert "reused from the cache" in run.stderr, run.stderr
    assert same_bits(ref, obscura.read_ao(out))
    # And the Python side reads what is there: the same image again.
    assert same_bits(obscura.reference(stairs, "hemisphere", cache=True, **args), ref)


def test_compare_returns_the_cli_report_metrics(cli, stairs, tmp_path):
    run = cli(
        "compare", "--scene", "stairs", "--size", "64x40", "--techniques", "vao,gtao",
        "--timing-frames", "0", "--no-cache", "--out", tmp_path / "report",
    )
    assert run.returncode == 0, run.stderr
    expected = json.loads((tmp_path / "report" / "report.json").read_text())
    report = obscura.compare(stairs, ["vao", "gtao"], width=64, height=40)
    assert [r["technique"] for r in report["results"]] == ["vao", "gtao"]
    for got, want in zip(report["results"], expected["results"]):
        for metric in ["mse", "mae", "psnr", "ssim", "halo_bright", "halo_dark", "settings"]:
            assert got[metric] == want[metric], (got["technique"], metric)
    assert report["reference"] == expected["reference"]
    assert report["camera"] == expected["camera"] == "closeup"
    # Metrics that say something: the rows differ from the truth, and from each other.
    assert 0 < report["results"][0]["mae"] != report["results"][1]["mae"]


def test_settings_dict_file_and_preset_resolve_as_the_library(tmp_path):
    s = obscura.settings("gtao", {"gtao": {"radius": 0.25}})
    assert s["technique"] == "gtao" and s["gtao"]["radius"] == 0.25
    (tmp_path / "s.json").write_text('{"gtao": {"radius": 0.25}}')
    assert obscura.settings("gtao", tmp_path / "s.json") == s
    # The technique may come from the settings alone.
    assert obscura.settings(None, {"technique": "hbao"})["technique"] == "hbao"
    # units convert every world length of the defaults.
    assert obscura.settings("gtao", units="cm")["gtao"]["radius"] == pytest.approx(
        100 * obscura.settings("gtao")["gtao"]["radius"]
    )


def test_a_time_budget_steers_the_rays_frame_after_frame(stairs):
    # hemisphere.time_budget follows each frame's GPU time, as `render --frames` does: a budget
    # far below any frame's time takes the rays of later frames away, a budget far above it
    # leaves them, so after a few frames the two images differ; after one frame (nothing
    # followed yet) they are the same.
    def ao(budget_ms, frames):
        settings = {"temporal.enabled": True, "hemisphere.time_budget": budget_ms}
        return obscura.render(stairs, "rtao", settings, width=64, height=48, frames=frames)

    assert same_bits(ao(1e-6, 1), ao(1e6, 1))
    starved, fed = ao(1e-6, 4), ao(1e6, 4)
    assert starved.dtype == np.float32 and np.all((starved >= 0) & (starved <= 1))
    assert float(np.mean(np.abs(starved - fed))) > 1e-3
