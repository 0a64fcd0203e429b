//! Tests of the shared option groups (args.rs): scenes and cameras, and settings from presets,
//! files, units and flags.

use super::*;
use crate::setting_flags::flag_for_field;
use clap::{CommandFactory, Parser};
use obscura::settings::SdMask;

#[derive(Parser)]
struct Cli {
    #[command(flatten)]
    ao: AoArgs,
}

fn ao(args: &[&str]) -> AoArgs {
    Cli::try_parse_from(std::iter::once("obscura").chain(args.iter().copied()))
        .unwrap_or_else(|e| panic!("{args:?}: {e}"))
        .ao
}

/// `--flag` → its help text.
fn helps() -> Vec<(String, String)> {
    Cli::command()
        .get_arguments()
        .filter_map(|a| {
            let long = a.get_long()?;
            Some((format!("--{long}"), a.get_help()?.to_string()))
        })
        .collect()
}

#[derive(Parser)]
struct SceneCli {
    #[command(flatten)]
    scene: SceneArgs,
}

#[test]
fn up_sets_the_camera_s_up_direction() {
    let camera = |args: &[&str]| {
        let cli = SceneCli::try_parse_from(std::iter::once("obscura").chain(args.iter().copied()))
            .unwrap_or_else(|e| panic!("{args:?}: {e}"));
        let scene = obscura::scene::builtin("stairs").unwrap();
        cli.scene.camera(&scene, 1.0).unwrap()
    };
    let view = ["--eye", "5,1,0", "--target", "0,1,0"];
    assert_eq!(camera(&view).up, Vec3::Y);
    let z_up = [&view[..], &["--up", "0,0,1"]].concat();
    assert_eq!(camera(&z_up).up, Vec3::Z);
}

#[test]
fn units_convert_the_defaults_world_lengths_and_flags_stay_in_scene_units() {
    let settings = |args: &[&str]| ao(args).settings(Technique::Vao).unwrap();
    let metres = settings(&[]);
    let cm = settings(&["--units", "cm"]);
    assert_eq!(cm, metres.scaled(100.0));
    assert!((cm.vao.radius - 50.0).abs() < 1e-4, "{}", cm.vao.radius);
    // SAO's intensity σ is dimensionless (issue 62): no unit converts it.
    assert_eq!(cm.sao.intensity, metres.sao.intensity);
    assert!((cm.blur.sharpness - metres.blur.sharpness / 100.0).abs() < 1e-9);
    assert_eq!(settings(&["--units", "0.001"]), metres.scaled(1000.0));
    assert_eq!(settings(&["--units", "m"]), metres);
    // A radius flag is in the scene's units, over the converted defaults.
    let flagged = settings(&["--units", "cm", "--radius", "20"]);
    assert_eq!(flagged.vao.radius, 20.0);
    assert_eq!(flagged.gtao.radius, cm.gtao.radius);
    for bad in ["0", "-1", "furlong", "inf", ""] {
        let err = ao(&["--units", bad])
            .settings(Technique::Vao)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("--units") && err.contains("metres"),
            "{bad}: {err}"
        );
    }
}

#[test]
fn every_settings_field_has_an_existing_flag() {
    let flags: Vec<String> = helps().into_iter().map(|(f, _)| f).collect();
    let fields = AoSettings::field_paths();
    for field in &fields {
        if field == "technique" {
            continue; // --technique / --techniques, per command
        }
        let knob = AoSettings::knob(field).unwrap_or_else(|| panic!("{field} has no knob"));
        for flag in knob.flags() {
            assert!(
                flags.iter().any(|f| f == flag),
                "{field}: {flag} is no flag"
            );
        }
    }
    for knob in AoSettings::knobs() {
        assert!(
            fields.iter().any(|f| f == knob.path),
            "{} is no field",
            knob.path
        );
    }
    assert_eq!(flag_for_field("vao.radius"), Some("--vao-radius"));
    assert_eq!(flag_for_field("stochastic_depth.alpha"), Some("--sd-alpha"));
}

#[test]
fn the_defaults_the_help_states_are_the_library_defaults() {
    let mut stated = 0;
    for (flag, help) in helps() {
        let Some((_, rest)) = help.split_once("[default: ") else {
            continue;
        };
        let value = rest.trim_end_matches(']');
        if flag == "--guard-band" {
            continue;
        }
        assert!(
            AoSettings::knob_for_flag(&flag).is_some(),
            "{flag} states a default but sets no field"
        );
        stated += 1;
        // Passing the stated default explicitly changes nothing, for every technique.
        let a = ao(&[&flag, value]);
        for t in Technique::all() {
            let want = AoSettings {
                technique: t,
                ..AoSettings::default()
            };
            assert_eq!(a.settings(t).unwrap(), want, "{flag} {value}");
        }
    }
    // Every field but the switches (--no-blur, --bent-normals, …), whose flags take no value.
    let switches = AoSettings::knobs()
        .filter(|k| matches!(k.kind, obscura::knob::Kind::Switch { .. }))
        .count();
    assert_eq!(stated, AoSettings::knobs().count() - switches);
    for t in Technique::all() {
        assert_eq!(
            ao(&[]).settings(t).unwrap(),
            AoSettings::preset(t, Preset::Medium)
        );
    }
}

#[test]
fn preset_then_file_then_flags() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("s.toml");
    std::fs::write(
        &file,
        "[vao]\nsamples = 16\nradius = 0.75\n[stochastic_depth]\nalpha = 0.5\n",
    )
    .unwrap();
    let f = file.to_str().unwrap();
    let t = Technique::SdSvao;
    let ultra = AoSettings::preset(t, Preset::Ultra);
    assert_eq!(ao(&["--preset", "ultra"]).settings(t).unwrap(), ultra);
    // The file over the preset: its fields win, the others stay the preset's.
    let s = ao(&["--preset", "ultra", "--settings", f])
        .settings(t)
        .unwrap();
    let mut want = ultra;
    want.vao.samples = 16;
    want.vao.radius = 0.75;
    want.stochastic_depth.alpha = Some(0.5);
    assert_eq!(s, want);
    // Flags over the file.
    let s = ao(&[
        "--settings",
        f,
        "--preset",
        "ultra",
        "--samples",
        "8",
        "--blur-radius",
        "3",
        "--sd-mask",
        "discard",
        "--no-blur",
    ])
    .settings(t)
    .unwrap();
    want.vao.samples = 8;
    want.blur.radius = 3;
    want.blur.enabled = false;
    want.stochastic_depth.mask = SdMask::Discard;
    assert_eq!(s, want);
    // No preset: the file over the defaults.
    let s = ao(&["--settings", f]).settings(Technique::Vao).unwrap();
    assert_eq!((s.vao.samples, s.vao.radius, s.blur.radius), (16, 0.75, 4));
    // The command line chooses the technique, not the file.
    let other = dir.path().join("t.json");
    std::fs::write(&other, r#"{"technique": "rt-vao"}"#).unwrap();
    let s = ao(&["--settings", other.to_str().unwrap()])
        .settings(Technique::Vao)
        .unwrap();
    assert_eq!(s.technique, Technique::Vao);
}

#[test]
fn one_radius_for_every_estimator_under_the_per_technique_flags() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("s.toml");
    std::fs::write(&file, "[vao]\nradius = 0.75\n[gtao]\nradius = 0.25\n").unwrap();
    let f = file.to_str().unwrap();
    // Over the preset and the file; under --hbao-radius.
    let args = ao(&[
        "--preset",
        "high",
        "--settings",
        f,
        "--ao-radius",
        "2",
        "--hbao-radius",
        "3",
    ]);
    // `--hbao-radius` is the old name of `--hbao-plus-radius`: it sets the rows whose radius is
    // `hbao_plus.radius`, and only those.
    let mut own_radius = 0;
    for t in Technique::all() {
        let s = args.settings(t).unwrap();
        let want = if t.estimator().caps().radius == "hbao_plus.radius" {
            own_radius += 1;
            3.0
        } else {
            2.0
        };
        assert_eq!(s.radius(), want, "{t}");
        // The ground truth's radius (`reference` and `compare` take `vao.radius`).
        assert_eq!(s.vao.radius, 2.0, "{t}");
    }
    assert!(own_radius > 0, "no row has the radius --hbao-radius sets");
    for bad in ["0", "-1", "inf", "NaN"] {
        let e = ao(&["--ao-radius", bad])
            .settings(Technique::Gtao)
            .unwrap_err();
        let e = e.to_string();
        assert!(
            e.starts_with(&format!("invalid --ao-radius {bad}:")),
            "{bad}: {e}"
        );
    }
}

#[test]
fn errors_name_flags_for_flags_and_fields_for_files() {
    let e = ao(&["--radius", "-1"])
        .settings(Technique::Vao)
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid --radius -1: must be a positive number of world units, e.g. 0.5"
    );
    let e = ao(&["--sd-alpha", "2"])
        .settings(Technique::SdVao)
        .unwrap_err();
    assert!(e.to_string().starts_with("invalid --sd-alpha 2:"), "{e}");
    let e = ao(&["--normalization", "flat"])
        .settings(Technique::Vao)
        .unwrap_err();
    assert!(
        e.to_string().starts_with("invalid --normalization flat:"),
        "{e}"
    );
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.toml");
    std::fs::write(&file, "[blur]\nradius = 40\n").unwrap();
    let e = ao(&["--settings", file.to_str().unwrap()])
        .settings(Technique::Vao)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("bad.toml") && e.contains("blur.radius 40") && !e.contains("--"),
        "{e}"
    );
    assert!(Cli::try_parse_from(["obscura", "--preset", "max"]).is_err());
}

/// `--help` groups the shared options under their own headings, and a command's own options
/// after them keep theirs (a heading set on a struct would carry over to them).
#[test]
fn shared_options_have_their_headings_and_the_command_s_own_keep_theirs() {
    #[derive(Parser)]
    struct Both {
        #[command(flatten)]
        scene: SceneArgs,
        #[arg(long)]
        size: Option<String>,
        #[command(flatten)]
        ao: AoArgs,
        #[arg(long)]
        out: Option<String>,
    }
    let command = Both::command();
    let heading = |long: &str| {
        let arg = command.get_arguments().find(|a| a.get_long() == Some(long));
        arg.unwrap_or_else(|| panic!("--{long}")).get_help_heading()
    };
    assert_eq!(heading("eye"), Some(SCENE_HEADING));
    assert_eq!(heading("normals"), Some(SCENE_HEADING));
    assert_eq!(heading("preset"), Some(SETTINGS_HEADING));
    assert_eq!(heading("units"), Some(SETTINGS_HEADING));
    assert_eq!(heading("size"), None);
    assert_eq!(heading("out"), None);
}
