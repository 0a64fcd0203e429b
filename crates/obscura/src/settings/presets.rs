//! Quality levels per technique ([`Preset`], [`AoSettings::preset`]).

use super::*;
use crate::knob::{Kind, Value};
use crate::technique::{PresetTable, Source};

/// A quality level: [`AoSettings::preset`] says per technique what each sets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Preset {
    /// The cheapest: blur radius 2 (VAO, HBAO+), fewer samples (HBAO 4 × 4, HBAO+ 4 directions,
    /// GTAO and GTAO-VB 1 × 2) and one stochastic depth sample per pixel.
    Low,
    /// The defaults ([`AoSettings::default`]) for every technique.
    #[default]
    Medium,
    /// More samples than the defaults where the estimator has room (VAO 16, HBAO 8 × 10, GTAO
    /// and GTAO-VB 3 × 3).
    High,
    /// The most samples (VAO 32, HBAO 16 × 20, GTAO 9 × 3, GTAO-VB 3 × 5, S = 8) and, for VAO
    /// and HBAO+, blur radius 6.
    Ultra,
}

impl Preset {
    /// Every preset, cheapest first.
    pub const ALL: [Preset; 4] = [Preset::Low, Preset::Medium, Preset::High, Preset::Ultra];

    /// The preset's name in settings files and on the command line (`low` … `ultra`).
    pub fn name(self) -> &'static str {
        match self {
            Preset::Low => "low",
            Preset::Medium => "medium",
            Preset::High => "high",
            Preset::Ultra => "ultra",
        }
    }
}

impl fmt::Display for Preset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Preset {
    type Err = SettingsError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let wanted = s.trim().to_ascii_lowercase();
        Preset::ALL
            .into_iter()
            .find(|p| p.name() == wanted)
            .ok_or_else(|| SettingsError::UnknownPreset(s.to_string()))
    }
}

impl AoSettings {
    /// The settings of `technique` at a quality level: [`AoSettings::default`] with the fields
    /// below changed, chosen by the axes of the technique's row (estimator, hidden-depth source;
    /// the schedule changes nothing: a two-phase technique gets the settings of its single-pass
    /// twin, so that both give the same image). Every other field keeps its default: a preset
    /// never changes the scene-dependent radius, thickness, exponent, normalisation, peel
    /// separation or blur sharpness, nor the seed or `sd-svao`'s mask (and the guard band is not
    /// a setting at all). `Medium` is exactly [`AoSettings::default`] for every technique.
    ///
    /// Per estimator and source (docs/SETTINGS.md has the table with every column): VAO
    /// `vao.samples` 8, 8, 16, 32 and `blur.radius` 2, 4, 4, 6; HBAO+ 4 × 4 directions × steps
    /// at low, else 8 × 4, `blur.radius` as VAO; HBAO directions × steps 4×4, 8×4, 8×10, 16×20;
    /// GTAO slices × steps 1×2, 2×2, 3×3, 9×3; GTAO-VB 1×2, 2×2, 3×3, 3×5; the
    /// stochastic depth map S = 1, 4, 4, 8 with α = 1.5/S throughout (at most 1: at S = 1 the
    /// nearest hidden surface).
    ///
    /// `low` keeps to one sample per pixel, which every adapter with the map's format rasterises
    /// (WebGPU guarantees 1× and 4× multisampling only).
    pub fn preset(technique: Technique, preset: Preset) -> AoSettings {
        let row = technique.row();
        let mut s = AoSettings {
            technique,
            ..AoSettings::default()
        };
        s.apply_preset(row.estimator.caps().presets, preset);
        s.apply_preset(row.source.caps().presets, preset);
        s
    }

    /// Sets every field of a preset table (an estimator's or a source's caps: a field's values
    /// at low, medium, high, ultra) to its value at `preset`.
    pub(crate) fn apply_preset(&mut self, table: &[(&str, [f64; 4])], preset: Preset) {
        let level = Preset::ALL
            .iter()
            .position(|p| *p == preset)
            .expect("a preset");
        for (path, values) in table {
            let knob = AoSettings::knob(path).expect("a preset names a settings field");
            let value = match knob.kind {
                Kind::Number { int: false, .. } => Value::Float(values[level]),
                _ => Value::Integer(values[level] as i64),
            };
            self.set_field(knob, Some(value))
                .expect("a preset's value is valid");
        }
    }

    /// docs/SETTINGS.md's preset table: one column per estimator and source that has presets
    /// (their caps literals' tables), the fields each sets, their values per preset.
    pub fn presets_markdown() -> String {
        // A march over a map takes the map's presets: one column per map.
        let mut sources: Vec<Source> = Vec::new();
        for t in Technique::all() {
            let source = t.source().map().unwrap_or(t.source());
            if !sources.contains(&source) {
                sources.push(source);
            }
        }
        let estimators = Estimator::all()
            .into_iter()
            .map(|e| (e.name(), e.caps().presets));
        let sources = sources.into_iter().map(|s| (s.name(), s.caps().presets));
        let columns: Vec<(&str, PresetTable)> = estimators
            .chain(sources)
            .filter(|(_, table)| !table.is_empty())
            .collect();
        let mut out = String::from("| preset |");
        for (name, table) in &columns {
            let fields: Vec<String> = table.iter().map(|(f, _)| format!("`{f}`")).collect();
            out.push_str(&format!(" {name}: {} |", fields.join(", ")));
        }
        out.push_str(&format!("\n|---|{}\n", "---|".repeat(columns.len())));
        for (level, preset) in Preset::ALL.into_iter().enumerate() {
            out.push_str(&format!("| `{preset}` |"));
            for (_, table) in &columns {
                let values: Vec<String> = table
                    .iter()
                    .map(|(_, v)| crate::knob::number(v[level]))
                    .collect();
                out.push_str(&format!(" {} |", values.join(", ")));
            }
            out.push('\n');
        }
        out
    }
}
