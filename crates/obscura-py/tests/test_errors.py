"""Bad input raises one clear exception, with the CLI's message, before any GPU work."""

import subprocess
import sys

import pytest

import obscura
from conftest import cli_error


def test_a_missing_scene_file_is_a_scene_error_with_the_clis_message(cli, tmp_path):
    missing = tmp_path / "nothing.glb"
    with pytest.raises(obscura.SceneError) as e:
        obscura.Scene(str(missing))
    message = cli_error(cli("render", "--scene", missing, "--out", tmp_path / "x.exr"))
    assert str(e.value) == message
    assert "does not exist" in message


def test_an_unknown_builtin_name_is_a_scene_error():
    with pytest.raises(obscura.SceneError, match="unknown scene 'stair'"):
        obscura.Scene("stair")


def test_a_bad_setting_names_its_field(stairs):
    with pytest.raises(obscura.SettingsError) as e:
        obscura.render(stairs, "vao", {"vao": {"radius": -1.0}}, width=32, height=32)
    assert e.value.path == "vao.radius"
    assert str(e.value).startswith("invalid vao.radius -1: ")
    assert isinstance(e.value, obscura.ObscuraError)


def test_a_bad_settings_file_has_the_clis_message_and_the_field(cli, stairs, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[gtao]\nslices = 0\n")
    with pytest.raises(obscura.SettingsError) as e:
        obscura.render(stairs, "gtao", str(bad), width=32, height=32)
    message = cli_error(
        cli("render", "--technique", "gtao", "--settings", bad, "--out", tmp_path / "x.exr")
    )
    assert str(e.value) == message
    assert e.value.path == "gtao.slices"


def test_unknown_fields_techniques_and_presets(stairs):
    with pytest.raises(obscura.SettingsError) as e:
        obscura.render(stairs, "vao", {"vao": {"radiu": 1}})
    assert e.value.path == "vao.radiu" and "vao.radius" in str(e.value)
    with pytest.raises(obscura.SettingsError) as e:
        obscura.render(stairs, "vao-typo")
    assert e.value.path == "technique" and "vao-typo" in str(e.value)
    with pytest.raises(obscura.SettingsError, match="unknown preset 'best'"):
        obscura.render(stairs, "vao", preset="best")
    with pytest.raises(obscura.SettingsError) as e:
        obscura.render(stairs, "vao", {"technique": "gtao"})
    assert e.value.path == "technique"
    with pytest.raises(obscura.SettingsError) as e:
        obscura.render(stairs, "vao", {"blur": {"enabled": [1]}})
    assert e.value.path == "blur.enabled"


def test_an_unknown_camera_is_a_camera_error(stairs):
    with pytest.raises(obscura.CameraError, match="nope"):
        obscura.render(stairs, "vao", camera="nope")
    with pytest.raises(obscura.CameraError):
        stairs.camera(eye=(0, 1, 0), target=(0, 1, 0))


def test_errors_come_before_any_gpu_work():
    # A backend that does not exist makes any device creation fail (GpuError): the bad inputs
    # must be reported first, so they are checked before a device is asked for.
    program = """
import obscura
scene = obscura.Scene("stairs")
for call, kind in [
    (lambda: obscura.render(scene, "vao", {"vao": {"radius": 0}}), obscura.SettingsError),
    (lambda: obscura.render(scene, "no-such-row"), obscura.SettingsError),
    (lambda: obscura.render(scene, "vao", camera="nope"), obscura.CameraError),
    (lambda: obscura.render(scene, "vao", width=0), obscura.InputError),
    (lambda: obscura.reference(scene, "vao", spp=4), obscura.InputError),
    (lambda: obscura.compare(scene, ["vao", "bad"]), obscura.SettingsError),
]:
    try:
        call()
    except kind:
        pass
    else:
        raise SystemExit("no error")
try:
    obscura.render(scene, "vao", width=16, height=16)
except obscura.GpuError:
    print("gpu refused last")
"""
    env = {"OBSCURA_BACKEND": "no-such-backend", "PATH": "/usr/bin:/bin"}
    run = subprocess.run(
        [sys.executable, "-c", program], capture_output=True, text=True, env=env, timeout=300
    )
    assert run.returncode == 0, run.stderr
    assert "gpu refused last" in run.stdout
