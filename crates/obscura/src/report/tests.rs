//! Tests of the report module: metrics on a hand-checkable fixture, the
//! written files, the heat map colours and every error path.

use super::heatmap::{diff_scale, nice_ceil};
use super::*;
use crate::metrics::MetricsError;
use std::collections::BTreeSet;
use std::fs;

const W: u32 = 32;
const H: u32 = 24;

/// A 32×24 fixture: a varied reference in [0.3, 0.8]; a depth step between
/// columns 15 (depth 1) and 16 (depth 5); techniques `same` (= reference),
/// `offset` (+0.1 everywhere) and `halo` (+0.2 in columns 14..=17 only, i.e.
/// brighter right next to the step).
struct Fixture {
    reference: Vec<f32>,
    depth: Vec<f32>,
    same: Vec<f32>,
    offset: Vec<f32>,
    halo: Vec<f32>,
}

impl Fixture {
    fn new() -> Self {
        let (w, h) = (W as usize, H as usize);
        let reference: Vec<f32> = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                0.3 + 0.5 * ((x * 7 + y * 13) % 17) as f32 / 16.0
            })
            .collect();
        let depth = (0..w * h)
            .map(|i| if i % w < 16 { 1.0 } else { 5.0 })
            .collect();
        let offset = reference.iter().map(|v| v + 0.1).collect();
        let halo = reference
            .iter()
            .enumerate()
            .map(|(i, v)| {
                if (14..=17).contains(&(i % w)) {
                    v + 0.2
                } else {
                    *v
                }
            })
            .collect();
        Fixture {
            same: reference.clone(),
            reference,
            depth,
            offset,
            halo,
        }
    }

    fn input(&self) -> ReportInput<'_> {
        ReportInput {
            scene: "cornell box",
            camera: "front",
            scene_options: "sides as authored, normals face",
            width: W,
            height: H,
            guard_band: 8,
            reference_model: "vao",
            spp: None,
            reference_radius: None,
            reference: &self.reference,
            depth: &self.depth,
            techniques: vec![
                TechniqueImage {
                    name: "same",
                    ao: &self.same,
                    settings: None,
                    gpu_ms: None,
                },
                TechniqueImage {
                    name: "offset",
                    ao: &self.offset,
                    settings: None,
                    gpu_ms: None,
                },
                TechniqueImage {
                    name: "halo",
                    ao: &self.halo,
                    settings: None,
                    gpu_ms: None,
                },
            ],
            halo_radius_px: 4,
            halo_relative_jump: 0.1,
            adapter: "Test Adapter <CPU & friends>",
            software_adapter: false,
            diff_scale: None,
            temporal: None,
        }
    }
}

fn result<'r>(report: &'r Report, name: &str) -> &'r TechniqueResult {
    report
        .results
        .iter()
        .find(|r| r.technique == name)
        .unwrap_or_else(|| panic!("no result for {name}"))
}

/// Equal, or both NaN, or within 2 ulp: serde_json's default float parser is
/// not always correctly rounded.
fn same_f64(a: f64, b: f64) -> bool {
    a == b
        || (a.is_nan() && b.is_nan())
        || (a - b).abs() <= 2.0 * f64::EPSILON * a.abs().max(b.abs())
}

fn assert_reports_match(a: &Report, b: &Report) {
    assert_eq!(
        (
            &a.scene,
            &a.camera,
            a.width,
            a.height,
            a.guard_band,
            &a.reference
        ),
        (
            &b.scene,
            &b.camera,
            b.width,
            b.height,
            b.guard_band,
            &b.reference
        )
    );
    assert_eq!(a.results.len(), b.results.len());
    for (x, y) in a.results.iter().zip(&b.results) {
        assert_eq!(x.technique, y.technique);
        for (u, v) in [
            (x.mse, y.mse),
            (x.mae, y.mae),
            (x.psnr, y.psnr),
            (x.ssim, y.ssim),
            (x.halo_bright, y.halo_bright),
            (x.halo_dark, y.halo_dark),
        ] {
            assert!(same_f64(u, v), "{}: {u} != {v}", x.technique);
        }
    }
}

fn names_in(dir: &Path) -> BTreeSet<String> {
    fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect()
}

/// Every quoted value of `attr="..."` in `html`.
fn attribute_values(html: &str, attr: &str) -> Vec<String> {
    let needle = format!("{attr}=\"");
    html.match_indices(&needle)
        .map(|(i, _)| {
            let rest = &html[i + needle.len()..];
            rest[..rest.find('"').expect("unterminated attribute")].to_owned()
        })
        .collect()
}

// ---------------------------------------------------------------- metrics

#[test]
fn build_report_metrics_match_hand_arithmetic() {
    let f = Fixture::new();
    let report = build_report(&f.input()).unwrap();
    assert_eq!(report.results.len(), 3);

    let same = result(&report, "same");
    assert_eq!(same.mse, 0.0);
    assert_eq!(same.mae, 0.0);
    assert_eq!(same.psnr, f64::INFINITY);
    assert!((same.ssim - 1.0).abs() < 1e-12, "ssim {}", same.ssim);
    assert_eq!((same.halo_bright, same.halo_dark), (0.0, 0.0));

    // +0.1 everywhere: e = 0.1 (up to f32 rounding of reference + 0.1), so
    // MSE = 0.1² = 0.01, MAE = 0.1, PSNR = 10·log10(1/0.01) = 20 dB; every
    // band pixel is 0.1 too bright.
    let offset = result(&report, "offset");
    assert!((offset.mse - 0.01).abs() < 1e-7, "mse {}", offset.mse);
    assert!((offset.mae - 0.1).abs() < 1e-6, "mae {}", offset.mae);
    assert!((offset.psnr - 20.0).abs() < 1e-4, "psnr {}", offset.psnr);
    assert!((offset.halo_bright - 0.1).abs() < 1e-6);
    assert_eq!(offset.halo_dark, 0.0);
    assert!(offset.ssim < 1.0);

    // Discontinuity pixels are columns 15 and 16; with radius 4 the band is
    // columns 11..=20 (10 columns). +0.2 in 4 of them: bright = 0.2·4/10.
    let halo = result(&report, "halo");
    assert!(halo.halo_bright > 0.0);
    assert!(
        (halo.halo_bright - 0.08).abs() < 1e-6,
        "{}",
        halo.halo_bright
    );
    assert_eq!(halo.halo_dark, 0.0);
    // MSE over the whole image: 0.04 on 4 of 32 columns.
    assert!((halo.mse - 0.04 * 4.0 / 32.0).abs() < 1e-7);

    assert_eq!(
        (report.scene.as_str(), report.camera.as_str()),
        ("cornell box", "front")
    );
    assert_eq!((report.width, report.height, report.guard_band), (W, H, 8));
    assert_eq!(
        report.reference,
        ReferenceInfo {
            model: "vao".into(),
            spp: None,
            radius: None,
        }
    );
    let order: Vec<_> = report
        .results
        .iter()
        .map(|r| r.technique.as_str())
        .collect();
    assert_eq!(order, ["same", "offset", "halo"]);
}

#[test]
fn build_report_writes_nothing() {
    let f = Fixture::new();
    let dir = tempfile::tempdir().unwrap();
    let before = names_in(dir.path());
    build_report(&f.input()).unwrap();
    assert_eq!(names_in(dir.path()), before);
}

// ------------------------------------------------------------------ files

#[test]
fn write_report_writes_every_file_consistently() {
    let f = Fixture::new();
    let dir = tempfile::tempdir().unwrap();
    let report = write_report(dir.path(), &f.input()).unwrap();
    assert_eq!(report, build_report(&f.input()).unwrap());

    let expected: BTreeSet<String> = [
        "index.html",
        "report.json",
        "report.md",
        "reference.png",
        "same.png",
        "same.diff.png",
        "offset.png",
        "offset.diff.png",
        "halo.png",
        "halo.diff.png",
    ]
    .into_iter()
    .map(String::from)
    .collect();
    // Exactly these: in particular no `.partial` file is left.
    assert_eq!(names_in(dir.path()), expected);

    for name in expected.iter().filter(|n| n.ends_with(".png")) {
        let dims = ::image::image_dimensions(dir.path().join(name)).unwrap();
        assert_eq!(dims, (W, H), "{name}");
    }

    // Grey PNGs hold the clamped, rounded AO.
    let grey = ::image::open(dir.path().join("reference.png"))
        .unwrap()
        .to_luma8();
    assert_eq!(grey.as_raw(), &files::grey8(&f.reference));
    let grey = ::image::open(dir.path().join("offset.png"))
        .unwrap()
        .to_luma8();
    assert_eq!(grey.as_raw(), &files::grey8(&f.offset));
}

#[test]
fn report_json_round_trips_with_null_for_infinite_psnr() {
    let f = Fixture::new();
    let dir = tempfile::tempdir().unwrap();
    let report = write_report(dir.path(), &f.input()).unwrap();
    let text = fs::read_to_string(dir.path().join("report.json")).unwrap();

    let parsed: Report = serde_json::from_str(&text).unwrap();
    assert_reports_match(&parsed, &report);
    assert_eq!(result(&parsed, "same").psnr, f64::INFINITY);

    // The raw JSON: `null` for the infinite PSNR, plain numbers elsewhere.
    let value: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert!(value["results"][0]["psnr"].is_null());
    assert!(value["results"][1]["psnr"].is_f64());
    assert!(value["reference"]["spp"].is_null());
    assert_eq!(value["reference"]["model"], "vao");
    assert_eq!(value["scene_options"], "sides as authored, normals face");
    assert_eq!(value["width"], W);
    // Pretty-printed.
    assert!(text.contains("\n  \"scene\": \"cornell box\""));
}

#[test]
fn json_null_rule_for_every_metric() {
    let r = TechniqueResult {
        technique: "x".into(),
        mse: f64::NAN,
        mae: 0.5,
        psnr: f64::INFINITY,
        ssim: f64::NEG_INFINITY,
        halo_bright: 0.25,
        halo_dark: -0.125,
        settings: None,
        gpu_ms: None,
    };
    let text = serde_json::to_string(&r).unwrap();
    assert_eq!(
        text,
        r#"{"technique":"x","mse":null,"mae":0.5,"psnr":null,"ssim":null,"halo_bright":0.25,"halo_dark":-0.125}"#
    );
    let back: TechniqueResult = serde_json::from_str(&text).unwrap();
    assert!(back.mse.is_nan() && back.ssim.is_nan());
    assert_eq!(back.psnr, f64::INFINITY);
    assert_eq!(
        (back.mae, back.halo_bright, back.halo_dark),
        (0.5, 0.25, -0.125)
    );
}

#[test]
fn index_html_is_self_contained_and_links_only_existing_files() {
    let f = Fixture::new();
    let dir = tempfile::tempdir().unwrap();
    write_report(dir.path(), &f.input()).unwrap();
    let html = fs::read_to_string(dir.path().join("index.html")).unwrap();

    for name in ["same", "offset", "halo"] {
        assert!(html.contains(&format!("<code>{name}</code>")), "{name}");
    }
    let srcs = attribute_values(&html, "src");
    // Reference once per technique, plus each technique and its heat map.
    assert_eq!(srcs.len(), 9);
    let mut referenced = BTreeSet::new();
    for link in srcs.iter().chain(&attribute_values(&html, "href")) {
        if let Some(id) = link.strip_prefix('#') {
            assert!(html.contains(&format!("id=\"{id}\"")), "dangling {link}");
            continue;
        }
        assert!(
            !link.contains(':') && !link.starts_with('/') && !link.contains(".."),
            "not a plain relative path: {link}"
        );
        assert!(dir.path().join(link).is_file(), "{link} does not exist");
        referenced.insert(link.clone());
    }
    for png in names_in(dir.path())
        .into_iter()
        .filter(|n| n.ends_with(".png"))
    {
        assert!(referenced.contains(&png), "{png} is not shown");
    }
    // No external resources, no script, inline CSS.
    assert!(!html.contains("://"));
    assert!(!html.contains("<script"));
    assert!(!html.contains("<link"));
    assert!(html.contains("<style>"));
    // The legend: the heat map's own colours and the ±scale labels. The
    // pooled |diff| is 0 on 1440 of 2304 values, 0.1 on 768, 0.2 on 96:
    // the 99th percentile is 0.2.
    assert!(html.contains("rgb(0, 0, 255), rgb(255, 255, 255), rgb(255, 0, 0)"));
    assert!(html.contains("<span>−0.2</span><span>0</span><span>+0.2</span>"));
    // Metrics table and halo explanations.
    assert!(html.contains("<td class=\"num\">∞</td>"));
    assert!(html.contains("Bright halo:") && html.contains("Dark halo:"));
    // Free text is escaped.
    assert!(html.contains("Test Adapter &lt;CPU &amp; friends&gt;"));
    assert!(!html.contains("<CPU"));
}

#[test]
fn heat_map_files_use_one_common_scale() {
    let f = Fixture::new();
    let dir = tempfile::tempdir().unwrap();
    write_report(dir.path(), &f.input()).unwrap();
    let rgb = |name: &str| {
        ::image::open(dir.path().join(name))
            .unwrap()
            .to_rgb8()
            .into_raw()
    };
    // Exact match: all white.
    assert!(rgb("same.diff.png").iter().all(|&c| c == 255));
    // +0.1 on the common scale 0.2: half way to red, (255, 127.5, 127.5).
    for px in rgb("offset.diff.png").chunks_exact(3) {
        assert_eq!(px[0], 255);
        assert!((127..=128).contains(&px[1]) && px[1] == px[2], "{px:?}");
    }
    // +0.2: pure red next to the step, white elsewhere.
    let halo = rgb("halo.diff.png");
    for (i, px) in halo.chunks_exact(3).enumerate() {
        let x = i % W as usize;
        let expected = if (14..=17).contains(&x) {
            [255, 0, 0]
        } else {
            [255, 255, 255]
        };
        assert_eq!(px, expected, "pixel {i}");
    }
}

#[test]
fn report_md_has_header_and_one_row_per_technique() {
    let f = Fixture::new();
    let dir = tempfile::tempdir().unwrap();
    let mut input = f.input();
    input.reference_model = "hemisphere";
    input.spp = Some(256);
    input.reference_radius = Some(0.75);
    write_report(dir.path(), &input).unwrap();
    let md = fs::read_to_string(dir.path().join("report.md")).unwrap();
    let lines: Vec<&str> = md.lines().collect();
    assert_eq!(
        lines[0],
        "# AO report: scene cornell box, camera front, 32×24, reference hemisphere, R = 0.75, \
         256 rays per pixel"
    );
    assert_eq!(
        lines[2],
        "| technique | MSE | MAE | PSNR (dB) | SSIM | bright halo | dark halo | GPU ms |"
    );
    assert_eq!(lines[3], "|:--|--:|--:|--:|--:|--:|--:|--:|");
    assert!(lines[4].starts_with("| `same` | 0.000e0 | 0.0000 | ∞ | 1.0000 |"));
    assert!(lines[5].starts_with("| `offset` | 1.000e-2 | 0.1000 | 20.00 |"));
    assert!(lines[6].starts_with("| `halo` |"));
    assert!(md.contains("Bright halo:") && md.contains("Dark halo:"));

    let json: Report =
        serde_json::from_str(&fs::read_to_string(dir.path().join("report.json")).unwrap()).unwrap();
    assert_eq!(json.reference.spp, Some(256));
    assert_eq!(json.reference.radius, Some(0.75));
}

#[test]
fn markdown_escapes_free_text() {
    let f = Fixture::new();
    let mut input = f.input();
    input.scene = "a|b *c*";
    input.camera = "line\nbreak";
    let report = build_report(&input).unwrap();
    let md = markdown::render(&report, &input, 0.1);
    assert!(md.starts_with("# AO report: scene a\\|b \\*c\\*, camera line break,"));
}

#[test]
fn rewriting_a_report_replaces_the_files() {
    let f = Fixture::new();
    let dir = tempfile::tempdir().unwrap();
    write_report(dir.path(), &f.input()).unwrap();
    let mut input = f.input();
    input.scene = "second run";
    write_report(dir.path(), &input).unwrap();
    let json: Report =
        serde_json::from_str(&fs::read_to_string(dir.path().join("report.json")).unwrap()).unwrap();
    assert_eq!(json.scene, "second run");
    assert!(!names_in(dir.path()).iter().any(|n| n.ends_with(".partial")));
}

// ---------------------------------------------------------------- heat map

#[test]
fn heatmap_endpoints_and_clamping() {
    let s = 0.2f32;
    let rgb = heatmap_rgb(&[0.0, s, -s, 0.5 * s, -0.5 * s, 7.0, -7.0], s);
    let px: Vec<&[u8]> = rgb.chunks_exact(3).collect();
    assert_eq!(px[0], [255, 255, 255]);
    assert_eq!(px[1], [255, 0, 0]);
    assert_eq!(px[2], [0, 0, 255]);
    assert_eq!(px[3], [255, 128, 128]);
    assert_eq!(px[4], [128, 128, 255]);
    assert_eq!(px[5], [255, 0, 0]);
    assert_eq!(px[6], [0, 0, 255]);
    assert!(heatmap_rgb(&[], s).is_empty());
}

#[test]
fn heatmap_is_monotonic() {
    let s = 0.1f32;
    let diffs: Vec<f32> = (-300..=300).map(|i| i as f32 * 1.5 * s / 300.0).collect();
    let rgb = heatmap_rgb(&diffs, s);
    assert_eq!(rgb.len(), diffs.len() * 3);
    for (i, pair) in rgb
        .chunks_exact(3)
        .collect::<Vec<_>>()
        .windows(2)
        .enumerate()
    {
        let (a, b) = (pair[0], pair[1]);
        assert!(b[0] >= a[0], "red decreased at {}", diffs[i + 1]);
        assert!(b[2] <= a[2], "blue increased at {}", diffs[i + 1]);
        if diffs[i + 1] <= 0.0 {
            assert!(b[1] >= a[1], "green decreased at {}", diffs[i + 1]);
        } else {
            assert!(b[1] <= a[1], "green increased at {}", diffs[i + 1]);
        }
    }
    // Inside ±scale a step of scale/200 moves the fading channels by 1.275
    // levels, so every sample there gets its own colour (401 of them).
    let distinct: BTreeSet<&[u8]> = rgb.chunks_exact(3).collect();
    assert!(distinct.len() > 300, "{}", distinct.len());
}

#[test]
fn heatmap_degenerate_inputs() {
    assert_eq!(heatmap_rgb(&[f32::NAN], 0.1), [0, 0, 0]);
    assert_eq!(heatmap_rgb(&[f32::INFINITY], 0.1), [255, 0, 0]);
    // Without a usable scale only the sign is shown.
    for bad in [0.0, -1.0, f32::NAN] {
        assert_eq!(
            heatmap_rgb(&[1e-6, 0.0, -1e-6], bad),
            [255, 0, 0, 255, 255, 255, 0, 0, 255]
        );
    }
}

#[test]
fn scale_is_rounded_up_to_a_nice_value() {
    let cases = [
        (0.0, 0.01),
        (0.003, 0.01),
        (0.01, 0.01),
        (0.011, 0.02),
        (0.03, 0.05),
        (0.05, 0.05),
        (0.07, 0.1),
        (f64::from(0.1f32), 0.1),
        (0.11, 0.2),
        (f64::from(0.2f32), 0.2),
        (0.3, 0.5),
        (0.6, 1.0),
        (1.0, 1.0),
        (1.5, 2.0),
        (7e40, 5e30),
    ];
    for (v, expected) in cases {
        assert_eq!(nice_ceil(v), expected, "nice_ceil({v})");
    }
    assert_eq!(format_scale(nice_ceil(0.04)), "0.05");
    assert_eq!(format_scale(nice_ceil(0.9)), "1");
}

#[test]
fn scale_is_the_99th_percentile_over_all_techniques() {
    let reference = vec![0.5f32; 500];
    // 990 of 1000 pooled differences are 0.03, 10 are 0.45: the 99th
    // percentile (nearest rank 990) is 0.03 → 0.05.
    let a: Vec<f32> = (0..500).map(|i| if i < 5 { 0.95 } else { 0.53 }).collect();
    let b: Vec<f32> = (0..500).map(|i| if i < 5 { 0.05 } else { 0.47 }).collect();
    assert_eq!(diff_scale(&reference, [&a[..], &b[..]].into_iter()), 0.05);
    // One more outlier moves rank 990 onto them → 0.5.
    let mut c = b.clone();
    c[5] = 0.05;
    assert_eq!(diff_scale(&reference, [&a[..], &c[..]].into_iter()), 0.5);
    // Identical images: the floor.
    assert_eq!(diff_scale(&reference, [&reference[..]].into_iter()), 0.01);
    assert_eq!(diff_scale(&reference, std::iter::empty()), 0.01);
}

#[test]
fn histogram_scale_equals_sorted_percentile() {
    // The constant-memory histogram must agree with the textbook definition:
    // sort the pooled |diff|, take nearest rank ceil(0.99 n), round up.
    let mut state = 0x9e37_79b9_u32;
    let mut next = move || {
        // xorshift32: deterministic pseudo-random values in [0, 1).
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state as f32 / 4_294_967_296.0
    };
    for (n, spread) in [(1, 0.3), (7, 0.05), (100, 0.9), (1000, 0.12), (4099, 0.02)] {
        let reference: Vec<f32> = (0..n).map(|_| next()).collect();
        let a: Vec<f32> = reference
            .iter()
            .map(|r| r + spread * (next() - 0.5))
            .collect();
        let b: Vec<f32> = reference
            .iter()
            .map(|r| r - spread * next() * next())
            .collect();
        let mut pooled: Vec<f32> = a
            .iter()
            .chain(&b)
            .zip(reference.iter().chain(&reference))
            .map(|(t, r)| (t - r).abs())
            .collect();
        pooled.sort_by(f32::total_cmp);
        let rank = (pooled.len() * 99).div_ceil(100);
        let expected = nice_ceil(f64::from(pooled[rank - 1]));
        let got = diff_scale(&reference, [&a[..], &b[..]].into_iter());
        assert_eq!(got, expected, "n = {n}, spread = {spread}");
    }
}

// ------------------------------------------------------------------ errors

/// Runs `write_report` on `input` into a fresh directory, expects an error,
/// checks that the directory is still empty and returns the error.
fn write_fails(input: &ReportInput) -> ReportError {
    let dir = tempfile::tempdir().unwrap();
    let err = write_report(dir.path(), input).expect_err("write_report should fail");
    assert_eq!(
        names_in(dir.path()),
        BTreeSet::new(),
        "files left after {err}"
    );
    // build_report rejects the same inputs.
    assert!(build_report(input).is_err());
    err
}

fn input_message(err: ReportError) -> String {
    match err {
        ReportError::Input(m) => m,
        other => panic!("expected ReportError::Input, got {other:?}"),
    }
}

#[test]
fn missing_directory_is_an_io_error_naming_it() {
    let f = Fixture::new();
    let parent = tempfile::tempdir().unwrap();
    let missing = parent.path().join("no-such-dir");
    let err = write_report(&missing, &f.input()).unwrap_err();
    let text = err.to_string();
    match err {
        ReportError::Io { path, message } => {
            assert_eq!(path, missing);
            assert!(message.contains("does not exist") && message.contains("create it"));
        }
        other => panic!("{other:?}"),
    }
    assert!(text.contains("no-such-dir"), "{text}");
    assert!(
        !missing.exists(),
        "write_report must not create the directory"
    );

    // A file is not a directory either.
    let file = parent.path().join("file");
    fs::write(&file, b"x").unwrap();
    let err = write_report(&file, &f.input()).unwrap_err();
    assert!(err.to_string().contains("not a directory"), "{err}");
    assert_eq!(fs::read(&file).unwrap(), b"x");
}

#[test]
fn wrong_slice_lengths_are_named() {
    let f = Fixture::new();
    let short = vec![0.5f32; (W * H - 1) as usize];

    let mut input = f.input();
    input.reference = &short;
    let m = input_message(write_fails(&input));
    assert!(
        m.starts_with("reference has 767 values") && m.contains("32x24 = 768"),
        "{m}"
    );

    let mut input = f.input();
    input.depth = &short;
    assert!(input_message(write_fails(&input)).starts_with("depth has 767 values"));

    let mut input = f.input();
    input.techniques[1].ao = &short;
    let m = input_message(write_fails(&input));
    assert!(m.starts_with("technique \"offset\" has 767 values"), "{m}");

    let mut input = f.input();
    input.width = 0;
    assert!(input_message(write_fails(&input)).contains("must both be positive"));
}

#[test]
fn bad_technique_names_are_rejected() {
    let f = Fixture::new();
    for (bad, suggestion) in [
        ("SSAO", "\"ssao\""),
        ("hbao plus", "\"hbao-plus\""),
        ("a/b", "\"a-b\""),
        ("../x", "\"---x\""),
        ("x.y", "\"x-y\""),
        ("", "\"technique\""),
        ("größe", "\"gr--e\""),
    ] {
        let mut input = f.input();
        input.techniques[0].name = bad;
        let m = input_message(write_fails(&input));
        assert!(m.contains(&format!("{bad:?}")), "{m}");
        assert!(
            m.contains("[a-z0-9") || m.contains("lowercase ASCII letters"),
            "{m}"
        );
        assert!(m.ends_with(suggestion), "{bad}: {m}");
    }
    let mut input = f.input();
    input.techniques[0].name = "reference";
    assert!(input_message(write_fails(&input)).contains("overwrite reference.png"));

    let mut input = f.input();
    input.techniques[2].name = "same";
    assert!(input_message(write_fails(&input)).contains("appears twice"));

    // Every allowed character.
    let mut input = f.input();
    input.techniques[0].name = "a-z_0+9";
    build_report(&input).unwrap();
}

#[test]
fn inconsistent_reference_model_and_spp_are_rejected() {
    let f = Fixture::new();
    for (model, spp, expect) in [
        ("path-traced", None, "unknown reference_model"),
        ("hemisphere", None, "needs spp"),
        ("hemisphere", Some(0), "needs spp"),
        ("vao", Some(16), "pass spp: None"),
    ] {
        let mut input = f.input();
        input.reference_model = model;
        input.spp = spp;
        let m = input_message(write_fails(&input));
        assert!(m.contains(expect), "{model} {spp:?}: {m}");
    }
    for radius in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        let mut input = f.input();
        input.reference_radius = Some(radius);
        let m = input_message(write_fails(&input));
        assert!(m.contains("reference_radius"), "{radius}: {m}");
    }
}

#[test]
fn other_invalid_inputs_are_rejected() {
    let f = Fixture::new();
    let mut input = f.input();
    input.techniques.clear();
    assert!(input_message(write_fails(&input)).contains("no techniques"));

    let mut nan = f.offset.clone();
    nan[2 * W as usize + 3] = f32::NAN;
    let mut input = f.input();
    input.techniques[1].ao = &nan;
    let m = input_message(write_fails(&input));
    assert!(
        m.contains("technique \"offset\"") && m.contains("(3, 2)"),
        "{m}"
    );

    // Errors the metrics report: too small for SSIM, bad halo parameter.
    let small = vec![0.5f32; 10 * 10];
    let mut input = f.input();
    (input.width, input.height) = (10, 10);
    (input.reference, input.depth) = (&small, &small);
    for t in &mut input.techniques {
        t.ao = &small;
    }
    let err = write_fails(&input);
    assert!(matches!(
        err,
        ReportError::Metrics(MetricsError::WindowTooLarge { .. })
    ));
    assert!(err.to_string().contains("11x11 window"), "{err}");

    let mut input = f.input();
    input.halo_relative_jump = -1.0;
    assert!(matches!(
        write_fails(&input),
        ReportError::Metrics(MetricsError::InvalidParameter { .. })
    ));
}

#[test]
fn a_failing_write_leaves_no_files_behind() {
    let f = Fixture::new();

    // The temporary file of the last output cannot be created: everything
    // staged before it must be removed again.
    let dir = tempfile::tempdir().unwrap();
    fs::create_dir(dir.path().join(".index.html.partial")).unwrap();
    let err = write_report(dir.path(), &f.input()).unwrap_err();
    match &err {
        ReportError::Io { path, message } => {
            assert_eq!(path, &dir.path().join("index.html"));
            assert!(message.contains(".index.html.partial"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    assert!(err.to_string().contains("index.html"));
    assert_eq!(
        names_in(dir.path()),
        BTreeSet::from([".index.html.partial".to_owned()])
    );

    // A directory where an output file should go.
    let dir = tempfile::tempdir().unwrap();
    fs::create_dir(dir.path().join("report.md")).unwrap();
    let err = write_report(dir.path(), &f.input()).unwrap_err();
    assert!(err.to_string().contains("report.md"), "{err}");
    assert!(err.to_string().contains("directory is in the way"), "{err}");
    assert_eq!(
        names_in(dir.path()),
        BTreeSet::from(["report.md".to_owned()])
    );
}

#[test]
fn errors_implement_std_error_and_display() {
    let e: Box<dyn std::error::Error + Send + Sync> =
        Box::new(ReportError::Input("reference has 3 values".into()));
    assert_eq!(
        e.to_string(),
        "invalid report input: reference has 3 values"
    );
    let e = ReportError::Io {
        path: PathBuf::from("/tmp/out/report.json"),
        message: "disk full".into(),
    };
    assert_eq!(
        e.to_string(),
        "could not write '/tmp/out/report.json': disk full"
    );
    let e = ReportError::from(MetricsError::Empty {
        width: 0,
        height: 3,
    });
    assert!(e
        .to_string()
        .starts_with("could not compute the report metrics: image is empty"));
}

// ------------------------------------------------------------- cost and time

fn timed(name: &str, mse: f64, ms: Option<f64>) -> TechniqueResult {
    TechniqueResult {
        technique: name.into(),
        mse,
        mae: 0.0,
        psnr: 0.0,
        ssim: 1.0,
        halo_bright: 0.0,
        halo_dark: 0.0,
        settings: None,
        gpu_ms: ms,
    }
}

#[test]
fn pareto_front_keeps_what_nothing_beats_on_both_counts() {
    let results = [
        timed("fast", 0.01, Some(1.0)),
        timed("slow-worse", 0.02, Some(2.0)),
        timed("slow-better", 0.001, Some(3.0)),
        timed("tie-fast", 0.01, Some(1.0)),
        timed("untimed", 0.0, None),
        timed("dominated", 0.01, Some(1.5)),
    ];
    // Equal on both counts: neither beats the other.
    assert_eq!(
        super::pareto_front(&results),
        vec!["fast", "slow-better", "tie-fast"]
    );
    assert!(super::pareto_front(&results[4..5]).is_empty());
}

#[test]
fn fixed_point_cells_never_print_negative_zero() {
    assert_eq!(super::fixed4(-0.00001), "0.0000");
    assert_eq!(super::fixed4(-0.0), "0.0000");
    assert_eq!(super::fixed4(0.00004), "0.0000");
    assert_eq!(super::fixed4(-0.00006), "-0.0001");
    assert_eq!(super::fixed4(0.25), "0.2500");
    assert_eq!(super::fixed4(f64::NAN), "n/a");
    let r = timed("x", 1e-3, Some(0.1234));
    assert_eq!(super::metric_cells(&r, false)[6], "0.123");
    assert_eq!(super::metric_cells(&r, true)[6], "0.1 (CPU)");
    assert_eq!(super::metric_cells(&timed("x", 1e-3, None), false)[6], "–");
}

#[test]
fn timed_reports_get_a_cost_chart_and_a_verdict() {
    let f = Fixture::new();
    let dir = tempfile::tempdir().unwrap();
    let mut input = f.input();
    for (t, ms) in input.techniques.iter_mut().zip([0.5, 0.2, 0.1]) {
        t.gpu_ms = Some(ms);
    }
    // A scale given by the caller (a page of several reports) is used as it is.
    input.diff_scale = Some(0.5);
    let report = write_report(dir.path(), &input).unwrap();
    assert_eq!(report.diff_scale, 0.5);
    assert_eq!(result(&report, "offset").gpu_ms, Some(0.2));
    let svg = fs::read_to_string(dir.path().join("cost.svg")).unwrap();
    for name in ["same", "offset", "halo"] {
        assert!(
            svg.contains(&format!(">{name}</text>")),
            "{name} not labelled"
        );
    }
    assert_eq!(svg.matches("<circle").count(), 3);
    let html = fs::read_to_string(dir.path().join("index.html")).unwrap();
    assert!(html.contains("src=\"cost.svg\""));
    assert!(html.contains("±0.5"), "the given scale is stated");
    // "same" equals the reference (MSE 0) but is the slowest; "halo" is the fastest.
    let verdict = super::verdict(&report);
    assert!(
        verdict.contains("halo") && verdict.contains("same"),
        "{verdict}"
    );
    let md = fs::read_to_string(dir.path().join("report.md")).unwrap();
    assert!(md.contains("Pareto front"), "{md}");
    let json: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(dir.path().join("report.json")).unwrap()).unwrap();
    assert_eq!(json["results"][1]["gpu_ms"], 0.2);
    assert_eq!(json["diff_scale"], 0.5);
    // Untimed: no chart.
    let dir = tempfile::tempdir().unwrap();
    write_report(dir.path(), &f.input()).unwrap();
    assert!(!dir.path().join("cost.svg").exists());
}
