//! Camera path interpolation, files and errors.

use glam::Vec3;

use super::*;

fn key(time: f32, eye: [f32; 3], target: [f32; 3], fov: f32) -> Keyframe {
    Keyframe {
        time,
        eye: Vec3::from(eye),
        target: Vec3::from(target),
        fov,
    }
}

fn curved() -> CameraPath {
    CameraPath::new(
        "curved",
        Interpolation::CatmullRom,
        vec![
            key(0.0, [0.0, 1.0, 5.0], [0.0, 1.0, 0.0], 50.0),
            key(1.0, [2.0, 1.5, 4.0], [0.0, 1.0, 0.0], 60.0),
            key(3.0, [4.0, 1.0, 1.0], [1.0, 0.0, 0.0], 40.0),
            key(3.5, [3.0, 2.0, -1.0], [0.0, 0.5, 0.0], 45.0),
        ],
    )
    .unwrap()
}

#[test]
fn passes_through_every_keyframe() {
    for interpolation in [Interpolation::CatmullRom, Interpolation::Linear] {
        let path = CameraPath {
            interpolation,
            ..curved()
        };
        for k in path.keyframes() {
            let c = path.camera_at(k.time).unwrap();
            assert!((c.eye - k.eye).length() < 1e-5, "{interpolation:?} {k:?}");
            let dir = (k.target - k.eye).normalize();
            assert!(
                (c.forward() - dir).length() < 1e-5,
                "{interpolation:?} {k:?}"
            );
            assert!(((c.target - c.eye).length() - (k.target - k.eye).length()).abs() < 1e-4);
            assert!((c.fov_y_deg - k.fov).abs() < 1e-5);
        }
    }
}

#[test]
fn catmull_rom_is_smooth_and_keeps_even_motion_even() {
    // C1 at interior keyframes: the velocity just before equals the velocity just after.
    let path = curved();
    let h = 1e-3;
    for k in &path.keyframes()[1..3] {
        let eye = |t: f32| path.camera_at(t).unwrap().eye;
        let before = (eye(k.time) - eye(k.time - h)) / h;
        let after = (eye(k.time + h) - eye(k.time)) / h;
        assert!(
            (before - after).length() < 0.02 * before.length().max(1.0),
            "t = {}: {before} vs {after}",
            k.time
        );
    }
    // Evenly spaced keyframes on a line, evenly timed: constant speed, so the spline equals the
    // straight line at every time.
    let line = CameraPath::new(
        "line",
        Interpolation::CatmullRom,
        (0..5)
            .map(|i| key(i as f32, [i as f32, 1.0, 3.0], [i as f32, 1.0, 0.0], 50.0))
            .collect(),
    )
    .unwrap();
    for t in [0.25, 1.5, 2.1, 3.9] {
        let eye = line.camera_at(t).unwrap().eye;
        assert!(
            (eye - Vec3::new(t, 1.0, 3.0)).length() < 1e-5,
            "t = {t}: {eye}"
        );
    }
}

#[test]
fn direction_turns_at_constant_rate_and_linear_eye_is_straight() {
    // 90° turn between two keyframes, same eye: at fraction u the view has turned u·90°.
    let path = CameraPath::new(
        "turn",
        Interpolation::Linear,
        vec![
            key(0.0, [0.0, 1.0, 0.0], [0.0, 1.0, -2.0], 50.0),
            key(2.0, [2.0, 1.0, 0.0], [4.0, 1.0, 0.0], 70.0),
        ],
    )
    .unwrap();
    for u in [0.1f32, 0.5, 0.8] {
        let c = path.camera_at(2.0 * u).unwrap();
        let angle = c.forward().angle_between(Vec3::NEG_Z);
        assert!(
            (angle - u * std::f32::consts::FRAC_PI_2).abs() < 1e-4,
            "u = {u}: {angle}"
        );
        assert!((c.eye - Vec3::new(2.0 * u, 1.0, 0.0)).length() < 1e-5);
        assert!((c.fov_y_deg - (50.0 + 20.0 * u)).abs() < 1e-4);
    }
    // Outside the range: clamped to the ends.
    assert_eq!(path.camera_at(-1.0).unwrap().eye, Vec3::new(0.0, 1.0, 0.0));
    assert_eq!(path.camera_at(9.0).unwrap().eye, Vec3::new(2.0, 1.0, 0.0));
}

#[test]
fn sampling_covers_the_whole_path() {
    let path = curved();
    let frames = path.sample(8).unwrap();
    assert_eq!(frames.len(), 8);
    assert_eq!(frames[0].0, 0.0);
    assert_eq!(frames[7].0, 3.5);
    assert!(frames.windows(2).all(|w| w[1].0 > w[0].0));
    assert_eq!(path.sample(1).unwrap()[0].0, 0.0);
    assert!(matches!(path.sample(0), Err(PathError::NoFrames)));
    // A single keyframe is a still camera.
    let still = CameraPath::new(
        "still",
        Interpolation::CatmullRom,
        vec![key(0.0, [0.0, 1.0, 2.0], [0.0, 0.0, 0.0], 50.0)],
    )
    .unwrap();
    let s = still.sample(3).unwrap();
    assert!(s.iter().all(|(_, c)| c.eye == Vec3::new(0.0, 1.0, 2.0)));
}

#[test]
fn json_round_trips_and_accepts_a_bare_list() {
    let path = curved();
    let back = CameraPath::from_json_str(&path.to_json(), "unused").unwrap();
    assert_eq!(back, path);
    let bare = r#"[{"time": 0, "eye": [0, 1, 3], "target": [0, 1, 0]},
                   {"time": 2, "eye": [1, 1, 3], "target": [0, 1, 0], "fov": 40}]"#;
    let p = CameraPath::from_json_str(bare, "walk").unwrap();
    assert_eq!(p.name, "walk");
    assert_eq!(p.interpolation, Interpolation::CatmullRom);
    assert_eq!(p.keyframes()[0].fov, 60.0);
    assert_eq!(p.keyframes()[1].fov, 40.0);
    let linear = r#"{"interpolation": "linear", "keyframes": [{"time": 0, "eye": [0, 1, 3], "target": [0, 1, 0]}]}"#;
    let p = CameraPath::from_json_str(linear, "file").unwrap();
    assert_eq!(
        (p.name.as_str(), p.interpolation),
        ("file", Interpolation::Linear)
    );
}

#[test]
fn bad_paths_name_the_problem() {
    let cases = [
        ("[]", "no keyframes"),
        (
            r#"[{"time": 1, "eye": [0,1,3], "target": [0,1,0]}, {"time": 1, "eye": [1,1,3], "target": [0,1,0]}]"#,
            "keyframe 1 has time 1",
        ),
        (
            r#"[{"time": 0, "eye": [0,1,3], "target": [0,1,3]}]"#,
            "keyframe 0",
        ),
        (
            r#"[{"time": 0, "eye": [0,1,3], "target": [0,1,0], "fov": 190}]"#,
            "keyframe 0",
        ),
        (
            r#"[{"time": 0, "eye": [0,1,3], "taget": [0,1,0]}]"#,
            "expected JSON",
        ),
        ("{not json", "expected JSON"),
    ];
    for (text, expected) in cases {
        let err = CameraPath::from_json_str(text, "bad")
            .unwrap_err()
            .to_string();
        assert!(err.contains(expected), "{text}: {err}");
        assert!(err.contains("bad"), "{text}: {err}");
    }
    let missing = std::path::Path::new("/nonexistent/obscura-path.json");
    let err = CameraPath::from_json_file(missing).unwrap_err().to_string();
    assert!(err.contains("/nonexistent/obscura-path.json"), "{err}");
}

#[test]
fn scenes_name_their_paths_and_files_get_an_orbit() {
    let stairs = crate::scene::builtin("stairs").unwrap();
    assert_eq!(stairs.path_names(), vec!["dolly".to_string()]);
    let err = stairs.path("orbit", 1.5).unwrap_err().to_string();
    assert!(err.contains("'orbit'") && err.contains("dolly"), "{err}");

    let mut file_scene = stairs.clone();
    file_scene.paths.clear();
    assert_eq!(file_scene.path_names(), vec!["orbit".to_string()]);
    let orbit = file_scene.path("orbit", 1.5).unwrap();
    let camera = file_scene.default_camera(1.5);
    let frames = orbit.sample(5).unwrap();
    // Same distance to the target throughout; 40° swept in total, symmetric about the camera.
    for (_, c) in &frames {
        assert!(
            ((c.eye - camera.target).length() - (camera.eye - camera.target).length()).abs() < 1e-4
        );
        assert!((c.target - camera.target).length() < 1e-4);
    }
    let (first, last) = (
        frames[0].1.eye - camera.target,
        frames[4].1.eye - camera.target,
    );
    let swept = Vec3::new(first.x, 0.0, first.z).angle_between(Vec3::new(last.x, 0.0, last.z));
    assert!((swept.to_degrees() - 40.0).abs() < 0.01, "{swept}");
    assert!((frames[2].1.eye - camera.eye).length() < 1e-4);
}
