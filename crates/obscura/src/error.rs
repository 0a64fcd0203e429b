//! The crate's errors: [`Error`], what every fallible call returns, and [`SettingsError`], what
//! can be wrong with settings (re-exported as `obscura::Error` and `obscura::settings::SettingsError`).

use crate::gpu::GpuError;
use crate::technique::UnknownTechnique;
use std::path::PathBuf;

/// Everything that can go wrong, each with a message that names the input and the fix.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The GPU failed: no adapter, no device, a validation error or an adapter limit.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// The AO settings are invalid (an out-of-range value, a technique's missing requirement).
    #[error(transparent)]
    Settings(#[from] SettingsError),
    /// An input the caller passed is unusable (a texture of the wrong size or format, a bad
    /// projection matrix, an unreadable image, an output path without a known extension); the
    /// message says which and how to fix it.
    #[error("{0}")]
    Input(String),
    /// Writing an output file failed; nothing half-written is left at `path`.
    #[error("could not write '{path}': {message}")]
    Output {
        /// The file that was being written.
        path: PathBuf,
        /// Why it failed (the encoder's or the file system's error).
        message: String,
    },
}

/// What can be wrong with settings. Messages name settings *fields* by their path in a settings
/// file (`vao.radius`, `stochastic_depth.alpha`), never a command-line flag: the CLI maps fields
/// to its flags itself.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SettingsError {
    /// A `technique` name that is not a row of the technique table.
    #[error(transparent)]
    UnknownTechnique(#[from] UnknownTechnique),
    /// A value no kernel can use.
    #[error("invalid {field} {value}: {rule}")]
    Invalid {
        /// The field's path, as in a settings file: `vao.radius`, `blur.radius`,
        /// `stochastic_depth.alpha`, `peel_separation`, … (one of [`AoSettings::field_paths`](crate::settings::AoSettings::field_paths)).
        field: &'static str,
        /// The rejected value, as given.
        value: String,
        /// What a valid value is, with an example; no command-line flags.
        rule: String,
    },
    /// A valid value the adapter cannot do (e.g. a stochastic depth sample count it cannot
    /// rasterise), with what it can do.
    #[error("{field} {value} is not supported on adapter '{adapter}': {reason}")]
    Unsupported {
        /// The field's path, as for [`SettingsError::Invalid`].
        field: &'static str,
        /// The value asked for, as given.
        value: String,
        /// The adapter's name.
        adapter: String,
        /// Why, and the values that work here.
        reason: String,
    },
    /// A settings field path that names no field (fields given by path:
    /// [`AoSettings::with_fields`](crate::settings::AoSettings::with_fields)).
    #[error("unknown settings field '{field}': {hint}")]
    UnknownField {
        /// The path as given.
        field: String,
        /// The fields of its section, or where they are listed.
        hint: String,
    },
    /// A preset name that is not one of [`Preset::ALL`](crate::settings::Preset::ALL).
    #[error("unknown preset '{0}': use low, medium, high or ultra")]
    UnknownPreset(String),
    /// A settings file whose extension says neither JSON nor TOML.
    #[error(
        "settings file '{}' is neither .json nor .toml: name it *.toml or *.json (the format is \
         chosen by the extension)",
        path.display()
    )]
    UnknownFormat {
        /// The settings file.
        path: PathBuf,
    },
    /// A settings file that cannot be read.
    #[error("cannot read settings file '{}': {message}: check the path", path.display())]
    Read {
        /// The settings file.
        path: PathBuf,
        /// The operating system's error.
        message: String,
    },
    /// A settings file that is not valid JSON/TOML, has a value of the wrong type or names a
    /// field that does not exist (`line`/`column` where the parser says, 1-based).
    #[error(
        "settings file '{}'{}: {message} (fix the file; its fields are listed in docs/SETTINGS.md)",
        path.display(),
        at(*line, *column)
    )]
    Parse {
        /// The settings file.
        path: PathBuf,
        /// The line the parser points at, 1-based; `None` where it cannot tell.
        line: Option<usize>,
        /// The column on that line, 1-based; `None` where the parser cannot tell.
        column: Option<usize>,
        /// The parser's message, without the position (`line`, `column` give it).
        message: String,
    },
    /// A settings file that parses but whose values do not validate.
    #[error("settings file '{}': {problem}", path.display())]
    InFile {
        /// The settings file.
        path: PathBuf,
        /// What [`AoSettings::validate`](crate::settings::AoSettings::validate) rejected in the
        /// file's values. Not named `source`: thiserror would make that the error's source too,
        /// and a chain printed whole (`{:#}`) would say it twice (issue 62).
        problem: Box<SettingsError>,
    },
}

/// Where in a settings file a parse error lies, for its message (empty where unknown).
fn at(line: Option<usize>, column: Option<usize>) -> String {
    match (line, column) {
        (Some(l), Some(c)) => format!(", line {l}, column {c}"),
        (Some(l), None) => format!(", line {l}"),
        _ => String::new(),
    }
}
