//! Settings from Python: a technique name, a preset, the scene's units and a dict of fields or a
//! settings file (TOML/JSON), made into `AoSettings` by the library's own steps
//! (`AoSettings::base`, `with_fields`, `with_file`), which the CLI uses too: the same words give
//! the same settings, checked by the same knobs.

use crate::errors::{from_settings, settings_error};
use obscura::knob::Value;
use obscura::settings::{AoSettings, Preset};
use obscura::Technique;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyString};
use std::path::PathBuf;

/// What a `settings=` argument holds.
pub enum Given {
    /// Fields by path (`vao.radius`), from a dict (nested or with dotted keys).
    Fields(Vec<(String, Option<Value>)>),
    /// A settings file, `.toml` or `.json`.
    File(PathBuf),
}

impl Given {
    /// `settings=`: None, a dict, or a path (str or os.PathLike).
    pub fn from_py(settings: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Given>> {
        let Some(obj) = settings else {
            return Ok(None);
        };
        if obj.is_none() {
            return Ok(None);
        }
        if let Ok(dict) = obj.cast::<PyDict>() {
            let mut fields = Vec::new();
            flatten(dict, "", &mut fields)?;
            return Ok(Some(Given::Fields(fields)));
        }
        match obj.extract::<PathBuf>() {
            Ok(path) => Ok(Some(Given::File(path))),
            Err(_) => Err(settings_error(
                format!(
                    "settings must be a dict of fields or the path of a .toml/.json settings \
                     file, not {}",
                    type_name(obj)
                ),
                None,
            )),
        }
    }

    /// The technique the settings name, if they do (a file is read for it: it names one where
    /// applied over `fallback`'s settings it leaves another, as the CLI reads a file over the
    /// technique it was asked for).
    fn technique(&self, fallback: Technique) -> PyResult<Option<Technique>> {
        match self {
            Given::Fields(fields) => {
                let mut s = AoSettings::default();
                for (path, value) in fields {
                    if path == "technique" {
                        s = s
                            .with_fields([(path.as_str(), value.clone())])
                            .map_err(from_settings)?;
                        return Ok(Some(s.technique));
                    }
                }
                Ok(None)
            }
            Given::File(path) => {
                let base = AoSettings {
                    technique: fallback,
                    ..AoSettings::default()
                };
                let s = base.with_file(path).map_err(from_settings)?;
                Ok((s.technique != fallback).then_some(s.technique))
            }
        }
    }
}

fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_else(|_| "that type".into())
}

/// Every leaf of a (nested) dict as `section.field` paths, in the dict's order.
fn flatten(
    dict: &Bound<'_, PyDict>,
    prefix: &str,
    out: &mut Vec<(String, Option<Value>)>,
) -> PyResult<()> {
    for (key, value) in dict.iter() {
        let key: String = key.extract().map_err(|_| {
            settings_error(
                format!("settings keys must be strings, not {}", type_name(&key)),
                None,
            )
        })?;
        let path = if prefix.is_empty() {
            key
        } else {
            format!("{prefix}.{key}")
        };
        if let Ok(inner) = value.cast::<PyDict>() {
            flatten(inner, &path, out)?;
        } else {
            let v = to_value(&value, &path)?;
            out.push((path, v));
        }
    }
    Ok(())
}

/// A Python value as a settings value: bool, int, float, str, or None (an optional field left
/// out).
fn to_value(value: &Bound<'_, PyAny>, path: &str) -> PyResult<Option<Value>> {
    if value.is_none() {
        return Ok(None);
    }
    // bool before int: Python's bool is an int.
    if value.is_instance_of::<PyBool>() {
        return Ok(Some(Value::Boolean(value.extract()?)));
    }
    if value.is_instance_of::<PyInt>() {
        return match value.extract::<i64>() {
            Ok(i) => Ok(Some(Value::Integer(i))),
            Err(_) => Err(settings_error(
                format!("invalid {path} {value}: the number is too large"),
                Some(path.to_string()),
            )),
        };
    }
    if value.is_instance_of::<PyFloat>() {
        return Ok(Some(Value::Float(value.extract()?)));
    }
    if value.is_instance_of::<PyString>() {
        return Ok(Some(Value::String(value.extract()?)));
    }
    Err(settings_error(
        format!(
            "invalid {path}: a settings value is a bool, number, string or None, not {}",
            type_name(value)
        ),
        Some(path.to_string()),
    ))
}

/// The settings of one call: `technique` (else the settings' own, else `vao`), its `preset`
/// (else the defaults) in the scene's `units`, then `given` over them; validated. Raises
/// `SettingsError` (with `.path`) before any GPU work.
pub fn resolve(
    technique: Option<&str>,
    given: Option<&Given>,
    preset: Option<&str>,
    units: Option<&str>,
) -> PyResult<AoSettings> {
    let asked = match technique {
        Some(name) => Some(
            name.parse::<Technique>()
                .map_err(|e| settings_error(e.to_string(), Some("technique".into())))?,
        ),
        None => None,
    };
    let named = match given {
        Some(g) => g.technique(asked.unwrap_or_default())?,
        None => None,
    };
    let technique = match (asked, named) {
        (Some(a), Some(n)) if a != n => {
            return Err(settings_error(
                format!(
                    "the settings set technique \"{n}\" but technique \"{a}\" was asked for: \
                     leave one of them out"
                ),
                Some("technique".into()),
            ))
        }
        (Some(t), _) | (None, Some(t)) => t,
        (None, None) => Technique::default(),
    };
    let preset = match preset {
        Some(p) => Some(p.parse::<Preset>().map_err(from_settings)?),
        None => None,
    };
    let units = match units {
        Some(u) => Some(
            obscura::settings::units_per_metre(u)
                .map_err(|rule| settings_error(format!("invalid units {u}: {rule}"), None))?,
        ),
        None => None,
    };
    let base = AoSettings::base(technique, preset, units);
    let settings = match given {
        None => {
            base.validate().map_err(from_settings)?;
            base
        }
        Some(Given::Fields(fields)) => base
            .with_fields(fields.iter().map(|(p, v)| (p.as_str(), v.clone())))
            .map_err(from_settings)?,
        Some(Given::File(path)) => base.with_file(path).map_err(from_settings)?,
    };
    Ok(settings)
}
