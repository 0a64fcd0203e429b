use super::*;
use std::path::PathBuf;

fn file(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn odd() -> AoSettings {
    let mut s = AoSettings::preset(Technique::SdSvao, Preset::Ultra);
    s.vao.radius = 0.7;
    s.vao.exponent = 1.1;
    s.vao.normalization = Normalization::Hemisphere;
    s.blur.enabled = false;
    s.blur.sharpness = 3.25;
    s.peel_separation = 0.05;
    s.stochastic_depth.seed = 17;
    s.stochastic_depth.mask = SdMask::Discard;
    s
}

#[test]
fn toml_and_json_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    for s in [AoSettings::default(), odd()] {
        let toml_text = s.to_toml_string();
        assert_eq!(toml::from_str::<AoSettings>(&toml_text).unwrap(), s);
        let json_text = s.to_json_string();
        assert_eq!(serde_json::from_str::<AoSettings>(&json_text).unwrap(), s);
        let t = file(dir.path(), "s.toml", &toml_text);
        assert_eq!(AoSettings::from_file(&t).unwrap(), s, "{toml_text}");
        let j = file(dir.path(), "s.JSON", &json_text);
        assert_eq!(AoSettings::from_file(&j).unwrap(), s, "{json_text}");
    }
    // Enums by their lowercase names, numbers as written.
    let text = odd().to_toml_string();
    for needle in [
        "technique = \"sd-svao\"",
        "normalization = \"hemisphere\"",
        "mask = \"discard\"",
        "radius = 0.7",
    ] {
        assert!(text.contains(needle), "{needle} not in\n{text}");
    }
    let json = AoSettings::default().to_json_string();
    assert!(json.contains("\"normalization\": \"clipped\""), "{json}");
    assert!(json.contains("\"mask\": \"depth\""), "{json}");
}

#[test]
fn a_partial_file_changes_only_its_fields() {
    let dir = tempfile::tempdir().unwrap();
    let t = file(dir.path(), "r.toml", "[vao]\nradius = 1.25\n");
    let mut want = AoSettings::default();
    want.vao.radius = 1.25;
    assert_eq!(AoSettings::from_file(&t).unwrap(), want);
    // Over a preset, the fields the file leaves out keep the preset's values.
    let base = AoSettings::preset(Technique::SdVao, Preset::Ultra);
    let mut want = base;
    want.vao.radius = 1.25;
    assert_eq!(base.with_file(&t).unwrap(), want);
    let j = file(
        dir.path(),
        "sd.json",
        r#"{"stochastic_depth": {"alpha": 0.5}, "peel_separation": 0}"#,
    );
    let mut want = base;
    want.stochastic_depth.alpha = Some(0.5);
    want.peel_separation = 0.0;
    assert_eq!(base.with_file(&j).unwrap(), want);
    let empty = file(dir.path(), "empty.toml", "");
    assert_eq!(base.with_file(&empty).unwrap(), base);
    let whole = file(dir.path(), "t.toml", "technique = \"rt-vao\"\n");
    assert_eq!(
        AoSettings::from_file(&whole).unwrap().technique,
        Technique::RtVao
    );
}

#[test]
fn bad_files_are_one_clear_error_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let check = |path: &Path, needles: &[&str]| {
        let e = AoSettings::from_file(path).unwrap_err();
        let msg = e.to_string();
        assert!(!msg.contains('\n'), "one line: {msg}");
        let name = path.file_name().unwrap().to_str().unwrap();
        for n in [name].iter().chain(needles) {
            assert!(msg.contains(n), "'{n}' not in: {msg}");
        }
        e
    };
    // Unknown fields, top level and nested, with the line.
    let e = check(
        &file(d, "typo.toml", "# comment\n[vao]\nradiu = 1.0\n"),
        &["radiu", "line 3", "radius"],
    );
    assert!(matches!(e, SettingsError::Parse { .. }), "{e:?}");
    check(
        &file(d, "typo.json", "{\n  \"peel_seperation\": 0.1\n}"),
        &["peel_seperation", "line 2"],
    );
    // Wrong types, unknown names, syntax errors.
    check(
        &file(d, "type.toml", "[vao]\nsamples = \"many\"\n"),
        &["line 2", "many"],
    );
    check(
        &file(d, "tech.toml", "technique = \"hbao-classic\"\n"),
        &["hbao-classic", "sd-svao"],
    );
    check(
        &file(d, "norm.toml", "[vao]\nnormalization = \"flat\"\n"),
        &["flat", "clipped"],
    );
    check(&file(d, "syntax.toml", "[vao\n"), &["line 1"]);
    check(
        &file(d, "syntax.json", "{\"vao\": {\"radius\": }}"),
        &["line 1"],
    );
    // Valid syntax, invalid value: the field and the rule, no CLI flag.
    let e = check(
        &file(d, "neg.toml", "[vao]\nradius = -1\n"),
        &["vao.radius", "-1", "positive"],
    );
    assert!(!e.to_string().contains("--"), "{e}");
    // Said once (issue 62: the invalid value was the error's source too, and `{:#}` said it
    // twice).
    assert!(std::error::Error::source(&e).is_none(), "{e:?}");
    // Not-a-numbers and infinities as written, not as the "null" of a JSON tree (issue 62).
    for text in ["nan", "inf", "-inf"] {
        let e = check(
            &file(d, "nan.toml", &format!("[vao]\nradius = {text}\n")),
            &["vao.radius", "positive"],
        );
        let msg = e.to_string();
        assert!(
            msg.to_lowercase().contains(&format!("radius {text}:")),
            "{msg}"
        );
        assert!(!msg.contains("null"), "{msg}");
    }
    // Unreadable, and a format the extension does not say.
    let e = check(&d.join("missing.toml"), &["cannot read", "check the path"]);
    assert!(matches!(e, SettingsError::Read { .. }));
    let e = check(&file(d, "s.yaml", "vao: {}"), &[".toml", ".json"]);
    assert!(matches!(e, SettingsError::UnknownFormat { .. }));
    check(&file(d, "noext", "[vao]"), &[".toml"]);
}

#[test]
fn presets_validate_and_medium_is_the_default() {
    for technique in Technique::all() {
        for preset in Preset::ALL {
            let s = AoSettings::preset(technique, preset);
            s.validate()
                .unwrap_or_else(|e| panic!("{technique} {preset}: {e}"));
            assert_eq!(s.technique, technique);
            // Never the scene-dependent or technique-independent fields.
            let d = AoSettings::default();
            assert_eq!(
                (s.vao.radius, s.vao.thickness, s.vao.exponent),
                (d.vao.radius, d.vao.thickness, d.vao.exponent)
            );
            assert_eq!(s.peel_separation, d.peel_separation);
            assert_eq!(s.blur.sharpness, d.blur.sharpness);
            assert_eq!(s.blur.enabled, d.blur.enabled);
        }
        assert_eq!(
            AoSettings::preset(technique, Preset::Medium),
            AoSettings {
                technique,
                ..AoSettings::default()
            }
        );
    }
    // The documented table.
    let vao = |p| {
        let s = AoSettings::preset(Technique::Vao, p);
        (s.vao.samples, s.blur.radius, s.stochastic_depth)
    };
    let sd_default = StochasticDepthSettings::default();
    assert_eq!(vao(Preset::Low), (8, 2, sd_default));
    assert_eq!(vao(Preset::High), (16, 4, sd_default));
    assert_eq!(vao(Preset::Ultra), (32, 6, sd_default));
    let hbao: Vec<_> = Preset::ALL
        .map(|p| {
            let s = AoSettings::preset(Technique::Hbao, p);
            (s.hbao.directions, s.hbao.steps)
        })
        .into();
    assert_eq!(hbao, [(4, 4), (8, 4), (8, 10), (16, 20)]);
    let gtao: Vec<_> = Preset::ALL
        .map(|p| {
            let s = AoSettings::preset(Technique::Gtao, p);
            (s.gtao.slices, s.gtao.steps)
        })
        .into();
    assert_eq!(gtao, [(1, 2), (2, 2), (3, 3), (9, 3)]);
    let sd = |p| {
        let s = AoSettings::preset(Technique::SdSvao, p);
        (
            s.vao.samples,
            s.stochastic_depth.samples,
            s.stochastic_depth.alpha(),
        )
    };
    assert_eq!(sd(Preset::Low), (8, 1, 1.0));
    assert_eq!(sd(Preset::Medium), (8, 4, 0.375));
    assert_eq!(sd(Preset::High), (16, 4, 0.375));
    assert_eq!(sd(Preset::Ultra), (32, 8, 0.1875));
    // A two-phase technique gets its single-pass twin's settings.
    for p in Preset::ALL {
        let (a, b) = (
            AoSettings::preset(Technique::SdVao, p),
            AoSettings::preset(Technique::SdSvao, p),
        );
        assert_eq!(
            AoSettings {
                technique: b.technique,
                ..a
            },
            b
        );
    }
    assert_eq!("ULTRA".parse::<Preset>().unwrap(), Preset::Ultra);
    let e = "max".parse::<Preset>().unwrap_err().to_string();
    assert!(e.contains("max") && e.contains("medium"), "{e}");
}

#[test]
fn a_radius_cap_is_none_or_at_least_a_pixel() {
    for bad in [0.5, -512.0, f32::NAN, f32::INFINITY] {
        let s = AoSettings {
            max_radius_px: bad,
            ..AoSettings::default()
        };
        let e = s.validate().unwrap_err().to_string();
        assert!(
            e.contains("max_radius_px") && e.contains("512"),
            "{bad}: {e}"
        );
    }
    for good in [0.0, 1.0, 512.0] {
        let s = AoSettings {
            max_radius_px: good,
            ..AoSettings::default()
        };
        s.validate().unwrap();
    }
}

#[test]
fn the_radius_is_the_estimators() {
    for technique in Technique::all() {
        let mut s = AoSettings::preset(technique, Preset::Medium);
        s.set_radius(1.75);
        assert_eq!(s.radius(), 1.75, "{technique}");
        let json = serde_json::to_string(&s).unwrap();
        assert_eq!(
            json.matches("1.75").count(),
            1,
            "{technique}: one radius field"
        );
    }
}

#[test]
fn every_radius_is_set_at_once() {
    for technique in Technique::all() {
        let mut s = AoSettings::preset(technique, Preset::High);
        s.set_every_radius(2.25);
        assert_eq!(s.radius(), 2.25, "{technique}");
        // The ground truth reads the VAO radius whatever the technique.
        assert_eq!(s.vao.radius, 2.25, "{technique}");
        // Every estimator's radius field (the test-only stub's too), and nothing else.
        let json = serde_json::to_string(&s).unwrap();
        let estimators = Estimator::all().len();
        assert_eq!(
            json.matches(":2.25").count(),
            estimators,
            "{technique}: {json}"
        );
        assert!(s.validate().is_ok(), "{technique}");
    }
}

#[test]
fn blur_sigma_is_a_natural_gaussian() {
    let mut b = BlurSettings {
        sigma: Some(1.5),
        ..BlurSettings::default()
    };
    for d in 1..=3 {
        let d2 = (d * d) as f32;
        let weight = (-d2 * b.falloff()).exp2();
        assert!(
            (weight - (-d2 / (2.0 * 1.5 * 1.5)).exp()).abs() < 1e-6,
            "d {d}"
        );
    }
    // Left out: HBAO+'s weights, σ' = (radius + 1)/2 in exp2 units.
    b.sigma = None;
    assert_eq!(b.falloff(), 1.0 / (2.0 * 2.5 * 2.5));
}

#[test]
fn validation_names_fields_that_exist_and_no_flags() {
    let paths = AoSettings::field_paths();
    // 89, and the test-only stub estimator's 2 (estimators/stub.rs).
    assert_eq!(paths.len(), 89 + 2, "{paths:?}");
    let mut broken: Vec<AoSettings> = Vec::new();
    let mut push = |f: &dyn Fn(&mut AoSettings)| {
        let mut s = AoSettings::default();
        f(&mut s);
        broken.push(s);
    };
    push(&|s| s.vao.radius = 0.0);
    push(&|s| s.vao.thickness = -1.0);
    push(&|s| s.vao.exponent = f32::NAN);
    push(&|s| s.vao.samples = 12);
    push(&|s| s.peel_separation = -0.1);
    push(&|s| s.stochastic_depth.samples = 3);
    push(&|s| s.stochastic_depth.alpha = Some(1.5));
    push(&|s| s.stochastic_depth.compensation = 0.5);
    push(&|s| s.stochastic_depth.guard_band = Some(4096));
    push(&|s| s.ray_sd.reservoir = 9);
    push(&|s| s.ray_sd.max_count = 2);
    push(&|s| s.ray_sd.resolution = 3);
    push(&|s| s.ray_sd.radius_cutoff = -1.0);
    push(&|s| s.ray_sd.guard_band = Some(4096));
    push(&|s| s.max_radius_px = 0.5);
    push(&|s| s.multiview.angle = 90.0);
    push(&|s| s.multiview.focus = Some(-1.0));
    push(&|s| s.blur.radius = 0);
    push(&|s| s.temporal.frames = 0);
    push(&|s| s.temporal.depth_tolerance = 1.0);
    push(&|s| s.temporal.normal_tolerance_deg = f32::NAN);
    push(&|s| s.blur.sharpness = -2.0);
    push(&|s| s.blur.sigma = Some(0.0));
    push(&|s| s.hbao_plus.radius = -1.0);
    push(&|s| s.hbao_plus.bias = 1.0);
    push(&|s| s.hbao_plus.exponent = 0.0);
    push(&|s| s.hbao_plus.directions = 0);
    push(&|s| s.hbao_plus.steps = 5);
    push(&|s| s.hbao.radius = 0.0);
    push(&|s| s.hbao.angle_bias = 1.6);
    push(&|s| s.hbao.exponent = f32::NAN);
    push(&|s| s.hbao.directions = 65);
    push(&|s| s.hbao.steps = 0);
    push(&|s| s.gtao.radius = -1.0);
    push(&|s| s.gtao.thickness_blend = 1.5);
    push(&|s| s.gtao.exponent = 0.0);
    push(&|s| s.gtao.slices = 17);
    push(&|s| s.gtao.steps = 33);
    push(&|s| s.pyramid.levels = 9);
    push(&|s| s.pyramid.factor = 1);
    push(&|s| s.pyramid_hbao.radius = f32::NAN);
    push(&|s| s.pyramid_hbao.exponent = -1.0);
    push(&|s| s.pyramid_hbao.directions = 0);
    push(&|s| s.pyramid_hbao.steps = 17);
    push(&|s| s.ssao.radius = -0.5);
    push(&|s| s.ssao.samples = 33);
    push(&|s| s.ssao.intensity = 0.0);
    push(&|s| s.ssao.bias = -1.0);
    push(&|s| s.ssao.contrast = f32::NAN);
    push(&|s| s.sao.radius = 0.0);
    push(&|s| s.sao.samples = 65);
    push(&|s| s.sao.spiral_turns = 0.0);
    push(&|s| s.sao.bias = -0.1);
    push(&|s| s.sao.intensity = f32::INFINITY);
    push(&|s| s.gtao_vb.radius = f32::INFINITY);
    push(&|s| s.gtao_vb.thickness = -0.5);
    push(&|s| s.gtao_vb.exponent = -1.0);
    push(&|s| s.gtao_vb.slices = 4);
    push(&|s| s.gtao_vb.steps = 9);
    push(&|s| s.hemisphere.time_budget = -1.0);
    push(&|s| {
        s.technique = Technique::Rtao;
        s.hemisphere.ray_budget = 1000;
    });
    let mut reported = Vec::new();
    for s in &broken {
        match s.validate() {
            Err(SettingsError::Invalid { field, rule, .. }) => {
                assert!(paths.iter().any(|p| p == field), "{field} not in {paths:?}");
                assert!(!rule.contains("--"), "{field}: '{rule}' names a flag");
                reported.push(field);
            }
            other => panic!("{s:?}: {other:?}"),
        }
    }
    reported.dedup();
    assert_eq!(reported.len(), broken.len(), "{reported:?}");
    for (text, field) in [
        ("flat".parse::<Normalization>().err(), "vao.normalization"),
        ("both".parse::<SdMask>().err(), "stochastic_depth.mask"),
        (
            "closest".parse::<SdSelection>().err(),
            "stochastic_depth.selection",
        ),
        ("often".parse::<SdQuery>().err(), "stochastic_depth.query"),
        (
            "software".parse::<SdRasterizer>().err(),
            "stochastic_depth.rasterizer",
        ),
        ("quarter".parse::<Resolution>().err(), "resolution"),
        (
            "half".parse::<SectorActivation>().err(),
            "gtao_vb.activation",
        ),
    ] {
        match text {
            Some(SettingsError::Invalid { field: f, .. }) => {
                assert_eq!(f, field);
                assert!(paths.iter().any(|p| p == f));
            }
            other => panic!("{other:?}"),
        }
    }
}

#[test]
fn the_depth_tolerance_stays_above_the_historys_rounding() {
    use super::MIN_TEMPORAL_DEPTH_TOLERANCE;
    let with = |tolerance: f32| {
        let mut s = AoSettings::default();
        s.temporal.depth_tolerance = tolerance;
        s.validate()
    };
    assert!(with(MIN_TEMPORAL_DEPTH_TOLERANCE).is_ok());
    assert!(with(0.03).is_ok());
    match with(MIN_TEMPORAL_DEPTH_TOLERANCE * 0.99) {
        Err(SettingsError::Invalid { field, rule, .. }) => {
            assert_eq!(field, "temporal.depth_tolerance");
            // The rule's literal names the same bound as the constant.
            assert!(
                rule.contains(&format!("[{MIN_TEMPORAL_DEPTH_TOLERANCE}, 1)")),
                "{rule}"
            );
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn the_fields_scaled_with_the_scene_are_those_the_docs_give_in_world_units() {
    // Every row of docs/SETTINGS.md's field table whose range names world units, and no other,
    // is in world_unit_fields(), with the power its range says.
    let docs = include_str!("../../../../docs/SETTINGS.md");
    let mut documented = Vec::new();
    for line in docs.lines().filter(|l| l.starts_with("| `")) {
        let cells: Vec<&str> = line.split(" | ").collect();
        let field = cells[0].trim_start_matches("| `").trim_end_matches('`');
        let range = cells.get(2).copied().unwrap_or("");
        if range.contains("per world unit") {
            documented.push((field.to_string(), -1));
        } else if range.contains("world units") {
            documented.push((field.to_string(), 1));
        }
    }
    let mut listed: Vec<(String, i32)> = AoSettings::world_unit_fields()
        .iter()
        .filter(|(f, _)| !f.starts_with("stub."))
        .map(|&(f, p)| (f.to_string(), p))
        .collect();
    documented.sort();
    listed.sort();
    assert_eq!(documented, listed);
    // And scaled() changes exactly those fields, by that power.
    let mut s = AoSettings::default();
    s.multiview.focus = Some(3.0);
    let scaled = s.scaled(4.0);
    let before = serde_json::to_value(s).unwrap();
    let after = serde_json::to_value(scaled).unwrap();
    for path in AoSettings::field_paths() {
        let pointer = format!("/{}", path.replace('.', "/"));
        let (b, a) = (&before.pointer(&pointer), &after.pointer(&pointer));
        match AoSettings::world_unit_fields()
            .iter()
            .find(|(f, _)| *f == path)
        {
            Some(&(_, power)) => {
                let (b, a) = (b.unwrap().as_f64().unwrap(), a.unwrap().as_f64().unwrap());
                assert!(
                    (a - b * 4f64.powi(power)).abs() <= 1e-6 * a.abs(),
                    "{path}: {b} -> {a}"
                );
            }
            None => assert_eq!(b, a, "{path} changed"),
        }
    }
}

#[test]
fn docs_settings_md_holds_the_field_table_the_knobs_make() {
    let docs = include_str!("../../../../docs/SETTINGS.md");
    // Without the test-only stub estimator's rows (estimators/stub.rs).
    let table: String = AoSettings::fields_markdown()
        .lines()
        .filter(|l| !l.starts_with("| `stub."))
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(
        docs.contains(&table),
        "docs/SETTINGS.md must hold this table (AoSettings::fields_markdown):\n{table}"
    );
}

#[test]
fn every_field_has_one_knob_and_every_knob_a_field() {
    let paths = AoSettings::field_paths();
    for path in paths.iter().filter(|p| *p != "technique") {
        let n = AoSettings::knobs().filter(|k| k.path == path).count();
        assert_eq!(n, 1, "{path}: {n} knobs");
    }
    let mut flags = std::collections::BTreeSet::new();
    for knob in AoSettings::knobs() {
        assert!(
            paths.iter().any(|p| p == knob.path),
            "{}: no field",
            knob.path
        );
        for flag in knob.flags() {
            assert!(flag.starts_with("--"), "{flag}");
            assert!(flags.insert(flag), "{flag} names two knobs");
        }
        // Every default satisfies its own knob.
        let default = AoSettings::default().to_tree();
        assert!(
            knob.accepts(crate::knob::get(&default, knob.path)),
            "{}",
            knob.path
        );
    }
}

#[test]
fn presets_name_fields_and_medium_is_the_default() {
    for technique in Technique::all() {
        assert_eq!(
            AoSettings::preset(technique, Preset::Medium),
            AoSettings {
                technique,
                ..AoSettings::default()
            },
            "{technique}"
        );
        for preset in Preset::ALL {
            AoSettings::preset(technique, preset).validate().unwrap();
        }
    }
}

/// An estimator's registry entry (estimators/mod.rs) and its caps literal alone give its fields
/// everything: flags (the CLI makes its flags of exactly `AoSettings::knobs`), checks, scaling,
/// presets, viewer widgets and docs/SETTINGS.md rows. The test-only stub (estimators/stub.rs)
/// has nothing else.
#[test]
fn a_registry_entry_gives_an_estimator_flags_checks_presets_widgets_and_docs() {
    use crate::knob::Widget;
    let stub = Estimator::Stub;
    assert!(Estimator::all().contains(&stub));
    let radius = AoSettings::knob_for_flag("--stub-radius").expect("a flag");
    assert_eq!(radius.path, "stub.radius");
    let mut s = AoSettings::default();
    s.set_field_text(radius, "0.25").unwrap();
    assert_eq!(s.stub.radius, 0.25);
    let e = s.set_field_text(radius, "-1").unwrap_err().to_string();
    assert_eq!(
        e,
        "invalid stub.radius -1: must be a positive number of world units, e.g. 0.5"
    );
    s.stub.samples = 99;
    let e = s.validate().unwrap_err().to_string();
    assert!(
        e.contains("stub.samples 99") && e.contains("between 1 and 32"),
        "{e}"
    );
    // Scaled with the scene, as a length.
    assert_eq!(AoSettings::default().scaled(4.0).stub.radius, 2.0);
    // Its presets, from its caps literal.
    for (preset, want) in Preset::ALL.into_iter().zip([4, 8, 16, 32]) {
        let mut p = AoSettings::default();
        p.apply_preset(stub.caps().presets, preset);
        assert_eq!(p.stub.samples, want, "{preset}");
    }
    // The viewer shows the knobs of a row's estimator section that have a widget.
    let shown: Vec<&str> = AoSettings::knobs()
        .filter(|k| k.section() == stub.section() && k.widget != Widget::Hidden)
        .map(|k| k.path)
        .collect();
    assert_eq!(shown, ["stub.radius", "stub.samples"]);
    // Its rows in docs/SETTINGS.md's table, and its field everywhere else.
    let table = AoSettings::fields_markdown();
    assert!(
        table.contains("| `stub.samples` | `--stub-samples` | 1 to 32 |"),
        "{table}"
    );
    assert!(AoSettings::field_paths().contains(&"stub.radius".to_string()));
    s.set_every_radius(3.0);
    assert_eq!(s.stub.radius, 3.0);
}

#[test]
fn the_raster_maps_band_defaults_to_the_ray_traced_maps_on_every_row() {
    // 512 px at 1080p scaled with the visible height, a multiple of 4 (92 px at 192 px high),
    // one-pass or not; a value given is kept, 0 included.
    let mut s = AoSettings::default();
    assert_eq!(s.stochastic_depth.guard_band, None);
    assert_eq!(s.stochastic_depth.guard_band_for(1080), 512);
    assert_eq!(s.stochastic_depth.guard_band_for(192), 92);
    assert_eq!(s.stochastic_depth.guard_band_for(64), 32);
    assert_eq!(
        s.stochastic_depth.guard_band_for(192),
        s.ray_sd.guard_band_for(192, true)
    );
    s.stochastic_depth.guard_band = Some(0);
    assert_eq!(s.stochastic_depth.guard_band_for(1080), 0);
    s.stochastic_depth.guard_band = Some(6);
    assert_eq!(s.stochastic_depth.guard_band_for(1080), 6);
}
