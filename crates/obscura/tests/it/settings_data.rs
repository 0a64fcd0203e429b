//! Settings as data: docs/SETTINGS.md stays equal to what the library does (the default file,
//! every field, the preset table), and the public file API from outside the crate.

use obscura::settings::{AoSettings, Preset, SettingsError, StochasticDepthSettings};
use obscura::technique::{Estimator, Source};
use obscura::Technique;

fn doc() -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/SETTINGS.md");
    std::fs::read_to_string(path).expect("docs/SETTINGS.md")
}

/// The first technique of the table with estimator `e`.
fn with_estimator(e: Estimator) -> Technique {
    Technique::all().find(|t| t.estimator() == e).unwrap()
}

/// The preset table of docs/SETTINGS.md, made by calling `AoSettings::preset`.
fn preset_table() -> String {
    let sd = Technique::all()
        .find(|t| t.source() == Source::StochasticDepth)
        .unwrap();
    let mut out = String::from(
        "| preset | VAO: `vao.samples`, `blur.radius` | HBAO: `hbao.directions` × `.steps` | HBAO+: `hbao_plus.directions` × `.steps`, `blur.radius` | GTAO: `gtao.slices` × `.steps` | GTAO-VB: `gtao_vb.slices` × `.steps` | Pyramid HBAO: `pyramid_hbao.directions` × `.steps` | SAO: `sao.samples` | SSAO: `ssao.samples` | stochastic depth: `stochastic_depth.samples` (S), `.alpha` (α) |\n|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for p in Preset::ALL {
        let at = |e| AoSettings::preset(with_estimator(e), p);
        let (v, hb, h, gt, g, ph, sao, ss, s) = (
            at(Estimator::Vao),
            at(Estimator::Hbao),
            at(Estimator::HbaoPlus),
            at(Estimator::Gtao),
            at(Estimator::GtaoVb),
            at(Estimator::PyramidHbao),
            at(Estimator::Sao),
            at(Estimator::Ssao),
            AoSettings::preset(sd, p),
        );
        out += &format!(
            "| `{p}` | {}, {} | {} × {} | {} × {}, {} | {} × {} | {} × {} | {} × {} | {} | {} | {}, {} |\n",
            v.vao.samples,
            v.blur.radius,
            hb.hbao.directions,
            hb.hbao.steps,
            h.hbao_plus.directions,
            h.hbao_plus.steps,
            h.blur.radius,
            gt.gtao.slices,
            gt.gtao.steps,
            g.gtao_vb.slices,
            g.gtao_vb.steps,
            ph.pyramid_hbao.directions,
            ph.pyramid_hbao.steps,
            sao.sao.samples,
            ss.ssao.samples,
            s.stochastic_depth.samples,
            s.stochastic_depth.alpha()
        );
    }
    out
}

#[test]
fn the_preset_table_is_the_whole_story() {
    let text = doc();
    let table = preset_table();
    assert!(
        text.contains(&table),
        "docs/SETTINGS.md must contain this preset table:\n{table}"
    );
    // The table holds for every technique: the VAO columns for every VAO-estimator technique,
    // the stochastic-depth ones for every technique with that source (the others keep the
    // defaults), and nothing else changes.
    let sd = Technique::all()
        .find(|t| t.source() == Source::StochasticDepth)
        .unwrap();
    for t in Technique::all() {
        for p in Preset::ALL {
            let s = AoSettings::preset(t, p);
            let mut want = AoSettings {
                technique: t,
                ..AoSettings::default()
            };
            let first = AoSettings::preset(with_estimator(t.estimator()), p);
            match t.estimator() {
                Estimator::Vao => {
                    want.vao.samples = first.vao.samples;
                    want.blur.radius = first.blur.radius;
                }
                Estimator::Hbao => want.hbao = first.hbao,
                Estimator::HbaoPlus => {
                    want.hbao_plus = first.hbao_plus;
                    want.blur.radius = first.blur.radius;
                }
                Estimator::Gtao => want.gtao = first.gtao,
                Estimator::PyramidHbao => want.pyramid_hbao = first.pyramid_hbao,
                Estimator::Sao => want.sao = first.sao,
                Estimator::Ssao => want.ssao = first.ssao,
                Estimator::GtaoVb => want.gtao_vb = first.gtao_vb,
            }
            want.stochastic_depth = if t.source() == Source::StochasticDepth {
                AoSettings::preset(sd, p).stochastic_depth
            } else {
                StochasticDepthSettings::default()
            };
            assert_eq!(s, want, "{t} {p}");
        }
    }
}

#[test]
fn the_documented_default_file_is_the_default() {
    let text = doc();
    let toml = AoSettings::default().to_toml_string();
    assert!(
        text.contains(&format!("```toml\n{toml}```")),
        "docs/SETTINGS.md must show the default file:\n{toml}"
    );
    for field in AoSettings::field_paths() {
        assert!(
            text.contains(&format!("| `{field}` |")),
            "docs/SETTINGS.md has no row for {field}"
        );
    }
}

#[test]
fn files_from_outside_the_crate() {
    let dir = tempfile::tempdir().unwrap();
    let t = dir.path().join("high-sd.toml");
    let mut s = AoSettings::preset(Technique::SdVao, Preset::High);
    s.vao.radius = 0.8;
    std::fs::write(&t, s.to_toml_string()).unwrap();
    assert_eq!(AoSettings::from_file(&t).unwrap(), s);
    let j = dir.path().join("high-sd.json");
    std::fs::write(&j, s.to_json_string()).unwrap();
    assert_eq!(AoSettings::from_file(&j).unwrap(), s);
    // Unknown fields are errors that name them.
    std::fs::write(&t, "[stochastic_depth]\nalfa = 0.5\n").unwrap();
    let e = AoSettings::from_file(&t).unwrap_err();
    assert!(
        matches!(e, SettingsError::Parse { line: Some(2), .. }),
        "{e:?}"
    );
    assert!(e.to_string().contains("alfa"), "{e}");
}
