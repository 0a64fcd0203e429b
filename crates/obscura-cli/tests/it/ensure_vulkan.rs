//! `scripts/ensure-vulkan.sh`, the README's first step, without root and without installing:
//! `--dry-run` prints the install command, a PATH of stand-ins decides which tools exist
//! (apt-get, sudo, Xvfb) and which user runs it (`id`), and ENSURE_VULKAN_ICD_DIRS which Vulkan
//! driver manifests there are.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scripts/ensure-vulkan.sh")
}

/// A folder of stand-in tools: `grep`, `pgrep` and `ldconfig` (the real ones, where present),
/// `id` printing `uid`, and each of `extra` as a program that succeeds.
fn tools(uid: u32, extra: &[&str]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for tool in ["grep", "pgrep", "ldconfig"] {
        let found = ["/usr/bin", "/bin", "/usr/sbin", "/sbin"]
            .iter()
            .map(|d| Path::new(d).join(tool))
            .find(|p| p.exists());
        if let Some(real) = found {
            std::os::unix::fs::symlink(real, dir.path().join(tool)).unwrap();
        }
    }
    let write = |name: &str, body: &str| {
        let path = dir.path().join(name);
        std::fs::write(&path, format!("#!/bin/sh\n{body}\n")).unwrap();
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    };
    write("id", &format!("echo {uid}"));
    for name in extra {
        write(name, "exit 0");
    }
    dir
}

/// The script run with `args` and the stand-ins, stdin empty (no terminal), a Vulkan driver
/// manifest present or not.
fn run(args: &[&str], tools: &Path, driver: bool) -> Output {
    let icd = tempfile::tempdir().unwrap();
    if driver {
        std::fs::write(icd.path().join("lvp_icd.x86_64.json"), "{}").unwrap();
    }
    // bash by its path: PATH holds only the stand-ins.
    let bash = ["/bin/bash", "/usr/bin/bash"]
        .into_iter()
        .find(|p| Path::new(p).exists())
        .expect("bash");
    Command::new(bash)
        .arg(script())
        .args(args)
        .env("PATH", tools)
        .env("ENSURE_VULKAN_ICD_DIRS", icd.path())
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap()
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

#[test]
fn nothing_missing_needs_no_root_and_prints_nothing() {
    // A user, no sudo, no apt-get: nothing to install, so none of them is needed.
    let t = tools(1000, &["Xvfb"]);
    let o = run(&["--dry-run"], t.path(), true);
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(text(&o), "");
    // The demo's call installs no Xvfb: without one it still needs nothing.
    let t = tools(1000, &[]);
    let o = run(&[], t.path(), true);
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(text(&o), "");
}

#[test]
fn xvfb_only_for_the_tests() {
    let t = tools(0, &["apt-get"]);
    let o = run(&["--dry-run"], t.path(), false);
    let out = text(&o);
    assert!(o.status.success(), "{out}");
    assert!(
        out.contains("install -y -qq mesa-vulkan-drivers libvulkan1"),
        "{out}"
    );
    assert!(!out.contains("xvfb"), "the demo needs no Xvfb: {out}");
    // Waits for a busy package manager instead of failing on its lock.
    assert!(out.contains("DPkg::Lock::Timeout="), "{out}");
    let o = run(&["--for-tests", "--dry-run"], t.path(), true);
    let out = text(&o);
    assert!(o.status.success(), "{out}");
    assert!(out.contains("xvfb"), "{out}");
    assert!(!out.contains("mesa-vulkan-drivers"), "{out}");
    // The Python package's tests make a virtual environment: no python3 among the stand-ins.
    assert!(out.contains("python3 python3-venv"), "{out}");
    let o = run(&["--dry-run"], t.path(), false);
    assert!(
        !text(&o).contains("python3"),
        "the demo needs no Python: {}",
        text(&o)
    );
}

#[test]
fn without_root_or_sudo_one_message_says_what_to_install() {
    let t = tools(1000, &["apt-get"]);
    let o = run(&["--dry-run"], t.path(), false);
    let out = text(&o);
    assert_eq!(o.status.code(), Some(1), "{out}");
    assert!(
        out.contains("needs root") && out.contains("apt-get install -y mesa-vulkan-drivers"),
        "{out}"
    );
    // With a sudo that works without a password, it goes through sudo.
    let t = tools(1000, &["apt-get", "sudo"]);
    let o = run(&["--dry-run"], t.path(), false);
    let out = text(&o);
    assert!(o.status.success(), "{out}");
    assert!(out.contains("would run: sudo apt-get"), "{out}");
    // No apt-get: what to install, in words.
    let t = tools(0, &[]);
    let o = run(&["--dry-run"], t.path(), false);
    let out = text(&o);
    assert_eq!(o.status.code(), Some(1), "{out}");
    assert!(out.contains("no apt-get"), "{out}");
}

#[test]
fn the_browser_and_node_only_for_the_web_tests() {
    let t = tools(0, &["apt-get"]);
    let o = run(&["--for-web", "--dry-run"], t.path(), true);
    let out = text(&o);
    assert!(o.status.success(), "{out}");
    assert!(out.contains("install -y -qq chromium nodejs npm"), "{out}");
    assert!(!out.contains("mesa-vulkan-drivers"), "{out}");
    // Present: nothing to install, no root needed.
    let t = tools(1000, &["chromium", "node", "npm"]);
    let o = run(&["--for-web", "--dry-run"], t.path(), true);
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(text(&o), "");
    // The other modes never ask for a browser.
    let t = tools(0, &["apt-get"]);
    let out = text(&run(&["--dry-run"], t.path(), false));
    assert!(!out.contains("chromium"), "{out}");
}

#[test]
fn an_unknown_argument_is_refused() {
    let t = tools(0, &[]);
    let o = run(&["--for-test"], t.path(), true);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("'--for-test'"), "{}", text(&o));
}

#[test]
fn the_readme_and_ci_run_the_same_test_command() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let ci = std::fs::read_to_string(root.join(".ci/run")).unwrap();
    let test_line = |text: &str| {
        text.lines()
            .find(|l| l.contains("cargo test --release --workspace"))
            .map(str::to_owned)
    };
    let line = test_line(&readme).expect("the README's test command");
    assert!(
        line.starts_with("bash scripts/ensure-vulkan.sh --for-tests && "),
        "{line}"
    );
    // The browser tests run after the Rust ones (issue 60).
    assert!(line.contains(" && bash scripts/web-tests.sh"), "{line}");
    assert_eq!(test_line(&ci), Some(line));
    // The demo's line installs no Xvfb.
    let demo = readme.lines().find(|l| l.contains("-- demo")).unwrap();
    assert!(!demo.contains("--for-tests"), "{demo}");
}
