//! The technique table as the page lists it (plain Rust: built and tested natively too).

/// Every technique row as JSON: `[{name, summary, paper, estimator, source, schedule,
/// hiddenDepth}]` (`hiddenDepth`: whether its source recovers what the depth buffer hides,
/// [`obscura::technique::Source::sees_hidden_geometry`]).
pub fn techniques_json() -> String {
    let rows: Vec<serde_json::Value> = obscura::Technique::all()
        .map(|t| {
            let row = t.row();
            serde_json::json!({
                "name": row.name,
                "summary": row.summary,
                "paper": row.paper,
                "estimator": row.estimator.name(),
                "source": row.source.name(),
                "schedule": row.schedule.name(),
                "hiddenDepth": row.source.sees_hidden_geometry(),
            })
        })
        .collect();
    serde_json::Value::Array(rows).to_string()
}

#[cfg(test)]
mod tests {
    #[test]
    fn rows_say_whether_they_see_hidden_geometry() {
        let rows: Vec<serde_json::Value> = serde_json::from_str(&super::techniques_json()).unwrap();
        assert_eq!(rows.len(), obscura::Technique::all().count());
        let hidden = |name: &str| {
            rows.iter().find(|r| r["name"] == name).unwrap()["hiddenDepth"]
                .as_bool()
                .unwrap()
        };
        for name in ["sd-vao", "rt-vao", "vao-dual", "ray-sd-hbao", "rtao"] {
            assert!(hidden(name), "{name}");
        }
        for name in ["vao", "gtao", "hbao+", "sao", "pyramid-hbao", "hemisphere"] {
            assert!(!hidden(name), "{name}");
        }
    }

    #[test]
    fn exr_bytes_are_the_clis_file() {
        let ao = [0.25f32, 0.5, 0.75, 1.0, 0.0, 0.125];
        let bytes = obscura::output::ao_exr_bytes(3, 2, &ao).unwrap();
        let dir = tempfile_dir();
        let path = dir.join("ao.exr");
        std::fs::write(&path, bytes).unwrap();
        let read = obscura::output::read_ao(&path).unwrap();
        assert_eq!((read.width, read.height), (3, 2));
        assert_eq!(read.values, ao);
        assert!(obscura::output::ao_exr_bytes(3, 3, &ao).is_err());
        std::fs::remove_dir_all(dir).unwrap();
    }

    /// A fresh folder under the system's temporary one (no dev-dependency for one test).
    fn tempfile_dir() -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("obscura-web-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }
}
