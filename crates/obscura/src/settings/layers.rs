//! How a front end makes settings from what its user gives, the same way in the CLI and the
//! Python package: the technique's preset (or the defaults) converted to the scene's units
//! ([`AoSettings::base`], [`units_per_metre`]), then a settings file
//! ([`AoSettings::with_file`]) or fields by path ([`AoSettings::with_fields`], the Python
//! package's dicts) over it, each field checked by its knob and the result validated.

use super::*;
use crate::knob::Value;

/// World units per metre from one world unit's length: metres as a number (`0.0254`) or a unit's
/// name (`m`, `cm`, `mm`, `km`, `in`, `ft`). In f64, so that `0.001` gives exactly 1000. The
/// error is the rule, without the option's name (the CLI says `--units`, Python `units=`).
pub fn units_per_metre(units: &str) -> Result<f32, String> {
    let metres: f64 = match units.trim() {
        "m" => 1.0,
        "cm" => 0.01,
        "mm" => 0.001,
        "km" => 1000.0,
        "in" => 0.0254,
        "ft" => 0.3048,
        number => number.parse().unwrap_or(f64::NAN),
    };
    let per_metre = (1.0 / metres) as f32;
    if !(metres > 0.0 && per_metre.is_finite() && per_metre > 0.0) {
        return Err(
            "give one world unit's length in metres (e.g. 0.01) or one of m, cm, mm, km, in, ft"
                .into(),
        );
    }
    Ok(per_metre)
}

impl AoSettings {
    /// The settings a front end starts from: `technique`'s `preset` (or the defaults), every
    /// world length converted for a scene with `units_per_metre` world units per metre
    /// ([`AoSettings::scaled`]; `None`: metres, nothing converted). A settings file or fields go
    /// over these, in the scene's own units.
    pub fn base(
        technique: Technique,
        preset: Option<Preset>,
        units_per_metre: Option<f32>,
    ) -> Self {
        let s = match preset {
            Some(preset) => AoSettings::preset(technique, preset),
            None => AoSettings {
                technique,
                ..AoSettings::default()
            },
        };
        match units_per_metre {
            Some(factor) => s.scaled(factor),
            None => s,
        }
    }

    /// `self` with the fields given by path replaced (`("vao.radius", Some(0.5))`; `None` leaves
    /// an optional field out, as a file that omits it: `stochastic_depth.alpha` = 1.5/S), each
    /// checked by its knob as the CLI's flags are, then validated as a whole. `technique` takes a
    /// row's name. An unknown path is [`SettingsError::UnknownField`]; on any error `self` is
    /// unchanged. A whole number is taken where a fractional one is expected.
    pub fn with_fields<'a>(
        &self,
        fields: impl IntoIterator<Item = (&'a str, Option<Value>)>,
    ) -> Result<AoSettings, SettingsError> {
        let mut s = *self;
        for (path, value) in fields {
            if path == "technique" {
                s.technique = match &value {
                    Some(Value::String(name)) => name.parse()?,
                    other => {
                        return Err(SettingsError::Invalid {
                            field: "technique",
                            value: crate::knob::show(other.as_ref()),
                            rule: "must be a technique's name, e.g. \"vao\"".into(),
                        })
                    }
                };
                continue;
            }
            let knob = Self::knob(path).ok_or_else(|| unknown_field(path))?;
            s.set_field(knob, value)?;
        }
        s.validate()?;
        Ok(s)
    }
}

/// [`SettingsError::UnknownField`] for `path`, with the fields of its section where it has one.
fn unknown_field(path: &str) -> SettingsError {
    let section = path.rsplit_once('.').map_or("", |(s, _)| s);
    let mut siblings: Vec<&str> = AoSettings::knobs()
        .filter(|k| k.section() == section)
        .map(|k| k.path)
        .collect();
    if section.is_empty() || siblings.is_empty() {
        siblings.clear();
    }
    let hint = match siblings.as_slice() {
        [] => "docs/SETTINGS.md lists every field".to_string(),
        fields => format!("the fields of '{section}' are {}", fields.join(", ")),
    };
    SettingsError::UnknownField {
        field: path.to_string(),
        hint,
    }
}
