//! Settings files, JSON or TOML ([`AoSettings::from_file`], [`AoSettings::with_file`] over a
//! preset), and the settings written back as either.

use super::*;

/// The format of a settings file, chosen by its extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SettingsFormat {
    /// `.json`
    Json,
    /// `.toml`
    Toml,
}

impl SettingsFormat {
    /// `.json` or `.toml` (any case); anything else is [`SettingsError::UnknownFormat`].
    pub fn of(path: &Path) -> Result<SettingsFormat, SettingsError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("json") => Ok(SettingsFormat::Json),
            Some("toml") => Ok(SettingsFormat::Toml),
            _ => Err(SettingsError::UnknownFormat {
                path: path.to_path_buf(),
            }),
        }
    }
}

/// Where a parser says it failed, 1-based.
struct ParseFailure {
    line: Option<usize>,
    column: Option<usize>,
    message: String,
}

/// One line, 1-based column, of byte `offset` in `text` (also the dataset spec's errors).
pub(crate) fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

fn parse<T: serde::de::DeserializeOwned>(
    text: &str,
    format: SettingsFormat,
) -> Result<T, ParseFailure> {
    match format {
        SettingsFormat::Json => serde_json::from_str(text).map_err(|e| {
            let full = e.to_string();
            let suffix = format!(" at line {} column {}", e.line(), e.column());
            let message = full.strip_suffix(&suffix).unwrap_or(&full).to_string();
            ParseFailure {
                line: (e.line() > 0).then_some(e.line()),
                column: (e.line() > 0).then_some(e.column()),
                message,
            }
        }),
        SettingsFormat::Toml => toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map(|span| line_column(text, span.start)).unzip();
            ParseFailure {
                line,
                column,
                message: e.message().trim().replace('\n', "; "),
            }
        }),
    }
}

/// `top`'s fields written over `base`'s, recursively.
fn merge(base: &mut serde_json::Value, top: serde_json::Value) {
    match (base, top) {
        (serde_json::Value::Object(base), serde_json::Value::Object(top)) => {
            for (key, value) in top {
                match base.get_mut(&key) {
                    Some(slot) => merge(slot, value),
                    None => {
                        base.insert(key, value);
                    }
                }
            }
        }
        (slot, value) => *slot = value,
    }
}

/// [`merge`] for TOML trees.
fn merge_toml(base: &mut toml::Value, top: toml::Value) {
    match (base, top) {
        (toml::Value::Table(base), toml::Value::Table(top)) => {
            for (key, value) in top {
                match base.get_mut(&key) {
                    Some(slot) => merge_toml(slot, value),
                    None => {
                        base.insert(key, value);
                    }
                }
            }
        }
        (slot, value) => *slot = value,
    }
}

impl AoSettings {
    /// A settings file (`.json` or `.toml`, by extension) over the defaults, validated. The file
    /// may give any subset of the fields ([`AoSettings::field_paths`]); an unknown field, a value
    /// of the wrong type or one [`AoSettings::validate`] rejects is an error naming the file (and
    /// the line where the parser can tell).
    pub fn from_file(path: impl AsRef<Path>) -> Result<AoSettings, SettingsError> {
        AoSettings::default().with_file(path)
    }

    /// `self` with the fields a settings file gives replaced by the file's, validated: how a
    /// file goes over a [`Preset`] (fields the file leaves out keep `self`'s values, not the
    /// defaults). Errors as [`AoSettings::from_file`].
    pub fn with_file(&self, path: impl AsRef<Path>) -> Result<AoSettings, SettingsError> {
        let path = path.as_ref();
        let format = SettingsFormat::of(path)?;
        let text = std::fs::read_to_string(path).map_err(|e| SettingsError::Read {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        self.with_text(&text, format, path)
    }

    /// [`AoSettings::with_file`] of a settings file's text already in memory (a web page's
    /// settings), `path` naming it in messages.
    pub fn with_text(
        &self,
        text: &str,
        format: SettingsFormat,
        path: &Path,
    ) -> Result<AoSettings, SettingsError> {
        let parse_error = |f: ParseFailure| SettingsError::Parse {
            path: path.to_path_buf(),
            line: f.line,
            column: f.column,
            message: f.message,
        };
        // Typed first, for the parser's positions on unknown fields and wrong types ...
        parse::<AoSettings>(text, format).map_err(parse_error)?;
        // ... then as a tree, to keep the fields the file leaves out.
        let merge_error = |message: String| SettingsError::Parse {
            path: path.to_path_buf(),
            line: None,
            column: None,
            message,
        };
        let settings: AoSettings = match format {
            SettingsFormat::Json => {
                let file: serde_json::Value = parse(text, format).map_err(parse_error)?;
                let mut merged = to_value(self);
                merge(&mut merged, file);
                serde_json::from_value(merged).map_err(|e| merge_error(e.to_string()))?
            }
            // TOML's own tree: it keeps `nan` and `inf`, which a JSON tree turns into null, so
            // that validation reports the value as written (issue 62: `radius = nan` was
            // reported as "invalid type: null").
            SettingsFormat::Toml => {
                let file: toml::Value = parse(text, format).map_err(parse_error)?;
                self.with_toml_unvalidated(file).map_err(merge_error)?
            }
        };
        settings.validate().map_err(|e| SettingsError::InFile {
            path: path.to_path_buf(),
            problem: Box::new(e),
        })?;
        Ok(settings)
    }

    /// `self` with the fields of `table` (a settings file's TOML tree, e.g. a table inside
    /// another TOML file such as a dataset spec) written over, not validated: the caller
    /// validates and names where the table came from. An unknown field or a value of the wrong
    /// type is an error with the parser's message.
    pub fn with_toml_unvalidated(&self, table: toml::Value) -> Result<AoSettings, String> {
        let mut merged = toml::Value::try_from(self).map_err(|e| e.to_string())?;
        merge_toml(&mut merged, table);
        merged
            .try_into()
            .map_err(|e: toml::de::Error| e.message().trim().replace('\n', "; "))
    }

    /// Every field as TOML (what a `.toml` settings file holds).
    pub fn to_toml_string(&self) -> String {
        toml::to_string(self).expect("AoSettings serialises to TOML")
    }

    /// Every field as pretty-printed JSON (what a `.json` settings file holds).
    pub fn to_json_string(&self) -> String {
        serde_json::to_string_pretty(self).expect("AoSettings serialises to JSON")
    }
}
