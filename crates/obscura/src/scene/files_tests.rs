//! Issue 62, defect 2: a scene file reads only regular files inside its own folder (unless
//! `allow_outside_files`), refuses without opening anything, and never echoes a file's bytes.

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

use super::test_dir::TestDir;
use super::{load_with, LoadOptions, Scene, SceneError};

/// What the refused files hold: no error may show any of it.
const SECRET: &[u8] = b"SECRET-0123456789-TOPSECRET";

fn assert_no_secret(message: &str) {
    // As text, as bytes in decimal (Debug of a byte array) and in hex.
    for word in ["SECRET", "0123", "TOPS", "83, 69", "5345", "53 45", "0x53"] {
        assert!(
            !message.contains(word),
            "the error echoes the file: {message}"
        );
    }
}

/// `scene/` (the scene's folder) and `secret.bin` beside it.
fn layout(tag: &str) -> (TestDir, PathBuf, PathBuf) {
    let root = TestDir::new(tag);
    let scene_dir = root.join("scene");
    std::fs::create_dir(&scene_dir).unwrap();
    let secret = root.join("secret.bin");
    std::fs::write(&secret, SECRET).unwrap();
    (root, scene_dir, secret)
}

/// Loads `path` on another thread: a load that blocks (on a FIFO) fails the test instead of
/// hanging it.
fn load_within(path: &Path, options: LoadOptions) -> Result<Scene, SceneError> {
    let (tx, rx) = mpsc::channel();
    let spec = path.to_str().unwrap().to_string();
    std::thread::spawn(move || {
        let _ = tx.send(load_with(&spec, &options));
    });
    rx.recv_timeout(Duration::from_secs(20))
        .unwrap_or_else(|_| panic!("loading {} hangs", path.display()))
}

/// A glTF whose only buffer is `uri`.
fn gltf_with_buffer(uri: &str) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"uri":"{uri}","byteLength":{}}}]}}"#,
        SECRET.len()
    )
}

fn expect_outside(err: SceneError, uri: &str) {
    let message = err.to_string();
    assert!(
        matches!(err, SceneError::OutsideFolder { .. }),
        "{uri}: {message}"
    );
    assert!(message.contains(&format!("'{uri}'")), "{message}");
    assert!(message.contains("--allow-outside-files"), "{message}");
    assert!(message.contains("outside the scene's folder"), "{message}");
    assert_no_secret(&message);
}

#[test]
fn gltf_buffers_outside_the_folder_are_refused() {
    let (_root, dir, secret) = layout("outside-gltf");
    let absolute = secret.canonicalize().unwrap();
    let absolute = absolute.to_str().unwrap();
    for uri in [
        "../secret.bin".to_string(),
        "%2e%2e/secret.bin".to_string(),
        "%2E%2E%2Fsecret.bin".to_string(),
        absolute.to_string(),
        format!("file://{absolute}"),
        format!("file:{absolute}"),
    ] {
        let scene = dir.join("scene.gltf");
        std::fs::write(&scene, gltf_with_buffer(&uri)).unwrap();
        let err = load_within(&scene, LoadOptions::default()).unwrap_err();
        expect_outside(err, &uri);
        // The opt-out reads it (the file then fails for want of meshes, not of its place), and
        // still does not echo it.
        let allowed = LoadOptions {
            allow_outside_files: true,
        };
        if let Err(e) = load_within(&scene, allowed) {
            assert!(!matches!(e, SceneError::OutsideFolder { .. }), "{e}");
            assert_no_secret(&e.to_string());
        }
    }
    // An image uri is checked as a buffer's is.
    let scene = dir.join("image.gltf");
    std::fs::write(
        &scene,
        r#"{"asset":{"version":"2.0"},"images":[{"uri":"../secret.bin"}]}"#,
    )
    .unwrap();
    expect_outside(
        load_within(&scene, LoadOptions::default()).unwrap_err(),
        "../secret.bin",
    );
    let allowed = LoadOptions {
        allow_outside_files: true,
    };
    for name in ["secret.bin", "secret.png", "secret.jpg"] {
        std::fs::copy(&secret, dir.join("..").join(name)).unwrap();
        let json = format!(r#"{{"asset":{{"version":"2.0"}},"images":[{{"uri":"../{name}"}}]}}"#);
        std::fs::write(&scene, json).unwrap();
        let err = load_within(&scene, allowed).unwrap_err().to_string();
        println!("allowed, not an image: {err}");
        assert_no_secret(&err);
    }
    // A symbolic link inside the folder to the file outside is outside.
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(&secret, dir.join("link.bin")).unwrap();
        std::fs::write(&scene, gltf_with_buffer("link.bin")).unwrap();
        expect_outside(
            load_within(&scene, LoadOptions::default()).unwrap_err(),
            "link.bin",
        );
    }
}

#[test]
fn obj_libraries_and_textures_outside_the_folder_are_refused() {
    let (_root, dir, _secret) = layout("outside-obj");
    let obj =
        |mtllib: &str| format!("mtllib {mtllib}\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n");
    std::fs::write(dir.join("../x.mtl"), "newmtl m\nKd 1 0 0\n").unwrap();
    let scene = dir.join("scene.obj");
    for mtllib in ["../x.mtl", "/dev/zero"] {
        std::fs::write(&scene, obj(mtllib)).unwrap();
        expect_outside(
            load_within(&scene, LoadOptions::default()).unwrap_err(),
            mtllib,
        );
    }
    // A texture of a library inside the folder, named by an absolute path.
    let absolute = dir.join("../secret.bin").canonicalize().unwrap();
    let absolute = absolute.to_str().unwrap();
    std::fs::write(
        dir.join("in.mtl"),
        format!("newmtl m\nKd 1 0 0\nmap_Kd {absolute}\n"),
    )
    .unwrap();
    std::fs::write(&scene, obj("in.mtl")).unwrap();
    expect_outside(
        load_within(&scene, LoadOptions::default()).unwrap_err(),
        absolute,
    );

    // The opt-out reads the library beside the folder (its red arrives), and refuses a device
    // all the same: it is not a regular file.
    let allowed = LoadOptions {
        allow_outside_files: true,
    };
    std::fs::write(&scene, obj("../x.mtl")).unwrap();
    let s = load_within(&scene, allowed).unwrap();
    assert_eq!(s.materials[0].base_color, [1.0, 0.0, 0.0, 1.0]);
    std::fs::write(&scene, obj("/dev/zero")).unwrap();
    let err = load_within(&scene, allowed).unwrap_err();
    assert!(matches!(err, SceneError::NotRegularFile { .. }), "{err}");
    assert!(err.to_string().contains("'/dev/zero'"), "{err}");
}

/// Makes a FIFO at `path`; false where `mkfifo` is not installed.
fn mkfifo(path: &Path) -> bool {
    match std::process::Command::new("mkfifo").arg(path).status() {
        Ok(status) => {
            assert!(status.success(), "mkfifo {} failed", path.display());
            true
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => false,
        Err(e) => panic!("mkfifo: {e}"),
    }
}

#[test]
fn fifos_are_refused_without_hanging() {
    let (_root, dir, _secret) = layout("fifo");
    if !mkfifo(&dir.join("pipe.bin")) {
        println!("skipped: no mkfifo on this machine");
        return;
    }
    let gltf = dir.join("scene.gltf");
    std::fs::write(&gltf, gltf_with_buffer("pipe.bin")).unwrap();
    let obj = dir.join("scene.obj");
    std::fs::write(
        &obj,
        "mtllib pipe.bin\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    for scene in [&gltf, &obj] {
        let err = load_within(scene, LoadOptions::default()).unwrap_err();
        assert!(matches!(err, SceneError::NotRegularFile { .. }), "{err}");
        assert!(err.to_string().contains("'pipe.bin'"), "{err}");
    }
    // The scene file itself.
    let fifo_scene = dir.join("fifo.obj");
    assert!(mkfifo(&fifo_scene));
    let err = load_within(&fifo_scene, LoadOptions::default()).unwrap_err();
    assert!(err.to_string().contains("not a regular file"), "{err}");
}

#[test]
fn files_inside_the_folder_still_load() {
    // A subfolder and a percent-encoded name are inside.
    let (_root, dir, _secret) = layout("inside");
    std::fs::create_dir(dir.join("mat")).unwrap();
    std::fs::write(dir.join("mat/a b.mtl"), "newmtl m\nKd 0 1 0\n").unwrap();
    let scene = dir.join("scene.obj");
    std::fs::write(
        &scene,
        "mtllib mat/a b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n",
    )
    .unwrap();
    let s = load_within(&scene, LoadOptions::default()).unwrap();
    assert_eq!(s.materials[0].base_color, [0.0, 1.0, 0.0, 1.0]);
}
