//! Settings as data: docs/SETTINGS.md stays equal to what the library does (the default file,
//! every field, the preset table), and the public file API from outside the crate.

use obscura::settings::{AoSettings, Preset, SettingsError};
use obscura::Technique;

fn doc() -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/SETTINGS.md");
    std::fs::read_to_string(path).expect("docs/SETTINGS.md")
}

#[test]
fn the_preset_table_is_the_whole_story() {
    let text = doc();
    let table = AoSettings::presets_markdown();
    assert!(
        text.contains(&table),
        "docs/SETTINGS.md must contain this preset table (AoSettings::presets_markdown):\n{table}"
    );
    // The table holds for every technique, and nothing else changes: a preset sets only the
    // fields its row's estimator and source name, medium is the defaults, every preset is valid.
    let defaults = |t| AoSettings {
        technique: t,
        ..AoSettings::default()
    };
    for t in Technique::all() {
        let named: Vec<&str> = t
            .estimator()
            .caps()
            .presets
            .iter()
            .chain(t.source().caps().presets)
            .map(|(field, _)| *field)
            .collect();
        for p in Preset::ALL {
            let s = AoSettings::preset(t, p);
            s.validate().unwrap();
            if p == Preset::Medium {
                assert_eq!(s, defaults(t), "{t}");
            }
            let (a, b) = (
                serde_json::to_value(s).unwrap(),
                serde_json::to_value(defaults(t)).unwrap(),
            );
            for field in AoSettings::field_paths() {
                let pointer = format!("/{}", field.replace('.', "/"));
                if a.pointer(&pointer) != b.pointer(&pointer) {
                    assert!(named.contains(&field.as_str()), "{t} {p}: {field} changed");
                }
            }
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
