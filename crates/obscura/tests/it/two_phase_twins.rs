//! Every two-phase row of the technique table gives the same image as its single-pass twin (the
//! row with the same estimator and source, scheduled in one pass): seed 000 §3.8/§3.9 present the
//! two-phase pipelines as an optimisation, not an approximation. Table-driven: a new two-phase row
//! is checked here without an edit (but for rtao-two-phase, tests/it/hemisphere.rs).

use crate::common::{gpu, max_abs_diff};
use obscura::scene;
use obscura::settings::{AoSettings, SdMask, StochasticDepthSettings};
use obscura::technique::{Schedule, Source, Technique, TechniqueRow, TABLE};
use obscura::Renderer;

/// Bound on |single - two-phase| per pixel (raw AO, no blur): the same arithmetic in another
/// order of passes; measured differences are below 5e-7.
const BOUND: f32 = 1e-5;

/// The settings sections whose knobs [`variants`] varies: a source's own section names them, so
/// a row over any source with that section gets its variants without an edit here.
const STOCHASTIC_DEPTH: &str = "stochastic_depth";
const RAY_SD: &str = "ray_sd";

/// The settings a source is checked with, per scene, by the knobs of its own settings section:
/// for the stochastic depth map both ways of limiting it and S = 1, 8 and 16; for the ray-traced
/// map its reservoir, intervals and guard band; for a source without knobs of its own (or none
/// listed here) its defaults. Each source also with the radius capped.
fn variants(source: Source, scene: &str) -> Vec<(String, AoSettings)> {
    let base = AoSettings::default();
    match source.section() {
        STOCHASTIC_DEPTH => {
            let mut samples = vec![4];
            match scene {
                "stairs" => samples.extend([8, 16]),
                "colonnade" => samples.push(1),
                _ => {}
            }
            let mut out = Vec::new();
            for s in samples {
                for mask in [SdMask::Stencil, SdMask::Depth, SdMask::Discard] {
                    let mut settings = base;
                    settings.stochastic_depth = StochasticDepthSettings {
                        samples: s,
                        alpha: Some(0.375),
                        seed: 7,
                        mask,
                        ..StochasticDepthSettings::default()
                    };
                    out.push((format!("S={s} {mask}"), settings));
                }
            }
            // Reading the map for every sample: phase 1 flags them all, and still the same image.
            let mut always = base;
            always.stochastic_depth.query = obscura::settings::SdQuery::Always;
            out.push(("S=4 query always".into(), always));
            out.push(("S=4 radius capped".into(), capped(base)));
            out
        }
        // The two-phase row's rays cover only the depths phase 1's samples need (ray intervals),
        // the single-pass twin's the whole ray, so their reservoirs see other hits: the images
        // agree without intervals, or with a reservoir that keeps every hit. The map's guard band
        // is set explicitly (its default differs by schedule: a one-pass row would trace all of
        // it); one variant has none, the others 40 px (1/1) or 48 px (1/4: 12 texels), which
        // 96×64 + 16 px samples leave often at the border.
        RAY_SD => {
            let mut base = base;
            base.ray_sd.guard_band = Some(40);
            let mut plain = base;
            plain.ray_sd.intervals = false;
            let mut small = plain;
            small.ray_sd.reservoir = 2;
            small.ray_sd.max_count = 3;
            small.ray_sd.z_cull = false;
            let mut large = base;
            large.ray_sd.reservoir = 8;
            large.ray_sd.max_count = 64;
            let mut no_band = plain;
            no_band.ray_sd.guard_band = Some(0);
            let mut quarter = large;
            quarter.ray_sd.resolution = 4;
            quarter.ray_sd.guard_band = Some(48);
            vec![
                ("no intervals, band 40 px".into(), plain),
                ("no intervals, no band".into(), no_band),
                ("N=2 MAX_COUNT=3 no z-cull, no intervals".into(), small),
                ("N=8 MAX_COUNT=64 with intervals".into(), large),
                ("N=8 MAX_COUNT=64 with intervals at 1/4".into(), quarter),
                (
                    "N=8 MAX_COUNT=64 with intervals, radius capped".into(),
                    capped(large),
                ),
            ]
        }
        _ => vec![
            ("defaults".into(), base),
            ("radius capped".into(), capped(base)),
        ],
    }
}

/// `s` with the AO radius capped at 8 px on screen (seed 002 §3.5), which binds on many pixels
/// of these 96×64 views: every phase must shrink R alike (phase 1's flags and ray intervals,
/// phase 2's values).
fn capped(s: AoSettings) -> AoSettings {
    AoSettings {
        max_radius_px: 8.0,
        ..s
    }
}

fn twin_of(row: &TechniqueRow) -> &'static TechniqueRow {
    TABLE
        .iter()
        .find(|t| {
            t.schedule == Schedule::Single && t.estimator == row.estimator && t.source == row.source
        })
        .unwrap_or_else(|| {
            panic!(
                "{}: no single-pass row with its estimator and source",
                row.name
            )
        })
}

#[test]
fn every_two_phase_row_equals_its_single_pass_twin() {
    let gpu = gpu();
    // A source whose section were renamed would fall to `variants`' defaults and lose its cases
    // without a failure: hold the names to the sources' own.
    for section in [STOCHASTIC_DEPTH, RAY_SD] {
        assert!(
            Source::all().any(|s| s.section() == section),
            "no source has the settings section `{section}`"
        );
    }
    // rtao-two-phase is the exception: phase 1 proves rays free from the depth buffer, which
    // misses geometry no pixel centre shows, so tests/it/hemisphere.rs holds that row to rtao with
    // a stated bound instead.
    let rows: Vec<_> = TABLE
        .iter()
        .filter(|r| r.schedule.two_phase() && r.technique != Technique::RtaoTwoPhase)
        .collect();
    assert!(!rows.is_empty());
    let mut compared = 0;
    for name in ["stairs", "colonnade", "grass"] {
        let scene = scene::builtin(name).unwrap();
        let camera = scene.cameras[0].camera;
        for row in &rows {
            let twin = twin_of(row);
            for (label, base) in variants(row.source, name) {
                let render = |row: &TechniqueRow| {
                    let mut settings = base;
                    settings.technique = row.technique;
                    settings.blur.enabled = false;
                    let mut r = Renderer::new(&gpu, &scene, &settings, 96, 64, 16).unwrap();
                    r.render(&camera, None).unwrap();
                    assert_eq!(r.read_stack_overflows().unwrap(), 0, "{name} {}", row.name);
                    r.read_ao().unwrap()
                };
                let single = render(twin);
                let two_phase = render(row);
                let worst = max_abs_diff(&single, &two_phase);
                println!(
                    "{name} {label}: max |{} - {}| {worst:.1e}",
                    twin.name, row.name
                );
                assert!(
                    worst <= BOUND,
                    "{name} {label}: max |{} - {}| {worst}",
                    twin.name,
                    row.name
                );
                assert!(
                    single.iter().any(|&v| v < 0.9),
                    "{name}: the view must have occlusion"
                );
                compared += 1;
            }
        }
    }
    println!("{compared} two-phase images compared with their twins'");
}
