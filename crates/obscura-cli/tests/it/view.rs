//! `obscura view` end to end: the real window, under Xvfb (a virtual X display, so CI and
//! machines without a screen run it too), runs a few frames, saves its image and exits; the image
//! must show the scene, not an empty or uniform frame. Xvfb is a test requirement like Mesa's
//! Vulkan driver: `scripts/ensure-vulkan.sh --for-tests` installs both, and without it this test fails
//! saying so instead of passing without having run.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The display pass's background (`display.wgsl`'s BACKGROUND as sRGB bytes).
const BACKGROUND: [u8; 3] = [31, 36, 46];

fn find_in_path(program: &str) -> Option<PathBuf> {
    std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|dir| dir.join(program))
            .find(|p| p.is_file())
    })
}

/// A private Xvfb server, stopped when dropped.
struct Xvfb {
    child: Child,
    display: String,
}

impl Xvfb {
    fn start() -> Xvfb {
        let Some(xvfb) = find_in_path("Xvfb") else {
            panic!(
                "Xvfb is not installed, and the viewer test needs it (a virtual display for the \
                 window): run `bash scripts/ensure-vulkan.sh --for-tests`, which installs it, or \
                 `sudo apt-get install xvfb`"
            );
        };
        // -displayfd: Xvfb picks a free display number and writes it to stdout when it is ready,
        // so parallel runs and other X servers never collide.
        let mut child = Command::new(xvfb)
            .args([
                "-displayfd",
                "1",
                "-screen",
                "0",
                "1280x800x24",
                "-nolisten",
                "tcp",
            ])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("start Xvfb");
        let mut line = String::new();
        BufReader::new(child.stdout.take().expect("piped"))
            .read_line(&mut line)
            .expect("read Xvfb's display number");
        let number = line.trim();
        assert!(
            !number.is_empty() && number.chars().all(|c| c.is_ascii_digit()),
            "Xvfb did not report a display number (got '{number}')"
        );
        Xvfb {
            display: format!(":{number}"),
            child,
        }
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// `obscura view` on `display` (X11 only), killed if it runs past two minutes.
fn view(display: &str, args: &[&str]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_obscura"))
        .arg("view")
        .args(args)
        .env("DISPLAY", display)
        .env_remove("WAYLAND_DISPLAY")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run obscura view");
    let start = Instant::now();
    while child.try_wait().expect("poll obscura view").is_none() {
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            break;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    child.wait_with_output().expect("obscura view output")
}

fn rgba(path: &Path) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
}

/// Standard deviation of the luminance (0–255) and the share of pixels that are not the
/// background colour.
fn content(image: &image::RgbaImage) -> (f64, f64) {
    let lum: Vec<f64> = image
        .pixels()
        .map(|p| 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]))
        .collect();
    let n = lum.len() as f64;
    let mean = lum.iter().sum::<f64>() / n;
    let sd = (lum.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / n).sqrt();
    let off_background = image
        .pixels()
        .filter(|p| {
            p.0[..3]
                .iter()
                .zip(BACKGROUND)
                .any(|(&c, b)| c.abs_diff(b) > 2)
        })
        .count() as f64
        / n;
    (sd, off_background)
}

fn assert_shows_the_scene(path: &Path, size: (u32, u32)) {
    let image = rgba(path);
    assert_eq!(image.dimensions(), size, "{}", path.display());
    let (sd, scene) = content(&image);
    // The stairs close-up: mostly geometry, AO from white to dark grey, some background.
    assert!(sd > 10.0, "{}: nearly uniform (sd {sd:.2})", path.display());
    assert!(
        scene > 0.5,
        "{}: only {:.0} % of the pixels show the scene",
        path.display(),
        100.0 * scene
    );
}

#[test]
fn view_runs_in_a_window_and_saves_what_it_shows() {
    let x = Xvfb::start();
    let dir = tempfile::tempdir().unwrap();
    let shot = dir.path().join("view.png");
    let shot_s = shot.to_str().unwrap();
    let o = view(
        &x.display,
        &[
            "--scene",
            "stairs",
            "--size",
            "320x200",
            "--frames",
            "5",
            "--screenshot",
            shot_s,
        ],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "obscura view failed: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert_shows_the_scene(&shot, (320, 200));
    // The whole window (panels included) came back from eframe too.
    let window = rgba(&dir.path().join("view.window.png"));
    assert!(window.width() >= 320 && window.height() >= 200);
    assert!(content(&window).0 > 10.0, "the window image is uniform");

    // Split screen with a two-phase stochastic-depth row on a CPU debug view, and the composite.
    for (view_name, extra) in [
        (
            "requested-pixels",
            ["--technique", "sd-svao", "--split", "hbao"],
        ),
        ("composite", ["--technique", "gtao", "--split", "vao"]),
    ] {
        let o = view(
            &x.display,
            &[
                &["--scene", "stairs", "--size", "160x100", "--frames", "3"][..],
                &["--view", view_name, "--screenshot", shot_s],
                &extra[..],
            ]
            .concat(),
        );
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "--view {view_name}: {err}");
        let (sd, _) = content(&rgba(&shot));
        assert!(sd > 10.0, "--view {view_name}: nearly uniform (sd {sd:.2})");
    }
}

#[test]
fn view_renders_offscreen_and_times_its_frames() {
    let dir = tempfile::tempdir().unwrap();
    let shot = dir.path().join("offscreen.png");
    let o = Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args([
            "view",
            "--scene",
            "stairs",
            "--size",
            "160x100",
            "--offscreen-frames",
            "2",
        ])
        .args(["--screenshot", shot.to_str().unwrap()])
        .output()
        .expect("run obscura view");
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.contains("frames/s"), "{out}");
    assert_shows_the_scene(&shot, (160, 100));
}

#[test]
fn view_rejects_bad_input_before_opening_a_window() {
    let dir = tempfile::tempdir().unwrap();
    let jpg = dir.path().join("x.jpg");
    for (args, needle) in [
        (vec!["--scene", "no-such-scene"], "unknown scene"),
        (vec!["--screenshot", jpg.to_str().unwrap()], ".png"),
        (vec!["--view", "nothing"], "unknown view"),
        (vec!["--frames", "0"], "1..=100000"),
        (vec!["--split", "nope"], "nope"),
    ] {
        // No display at all: every one of these must fail before a window is tried.
        let o = Command::new(env!("CARGO_BIN_EXE_obscura"))
            .arg("view")
            .args(&args)
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .expect("run obscura view");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} should fail");
        assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
        assert!(err.contains(needle), "{args:?}: '{needle}' not in {err}");
    }
}
