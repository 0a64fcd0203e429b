//! The settings flags: one per settings field, made from the library's knob declarations
//! (`obscura::knob`, the `KNOBS` lists beside the settings structs), so no flag, help text,
//! range or default is written here. An older flag name is its own hidden argument, so that an
//! error names the flag as typed (`invalid --radius -1: …`).

use anyhow::anyhow;
use clap::{Arg, ArgAction, ArgMatches, Command};
use obscura::knob::{Kind, Knob};
use obscura::settings::{AoSettings, SettingsError};
use obscura::technique::{Schedule, TechniqueRow, TABLE};
use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};

/// The setting flags given, in the knobs' order (the order of docs/SETTINGS.md), each with the
/// name it was given by and its text (a switch's: the value it sets).
#[derive(Clone, Debug, Default)]
pub struct SettingFlags(pub Vec<(&'static str, &'static Knob, String)>);

impl SettingFlags {
    /// Applies every flag given to `settings`; an error names the flag as typed.
    pub fn apply(&self, settings: &mut AoSettings) -> anyhow::Result<()> {
        for (flag, knob, text) in &self.0 {
            settings
                .set_field_text(knob, text)
                .map_err(|e| named(e, Some(flag)))?;
        }
        Ok(())
    }

    /// The flag given for settings field `path`, if any.
    pub fn given_for(&self, path: &str) -> Option<&'static str> {
        self.0
            .iter()
            .rev()
            .find(|(_, k, _)| k.path == path)
            .map(|(f, _, _)| *f)
    }
}

/// The argument id of a flag: its name without the dashes.
fn id(flag: &'static str) -> &'static str {
    flag.trim_start_matches("--")
}

/// `--help`'s group of a section's flags: the estimator's or source's whose section it is, with
/// the rows that read it (from the technique table), or the settings every technique has.
fn heading(section: &'static str) -> &'static str {
    // Made once per section (clap keeps help headings as `&'static str`: each is leaked once).
    static HEADINGS: OnceLock<Mutex<HashMap<&str, &'static str>>> = OnceLock::new();
    let mut headings = HEADINGS
        .get_or_init(Default::default)
        .lock()
        .expect("not poisoned");
    headings
        .entry(section)
        .or_insert_with(|| make_heading(section))
}

fn make_heading(section: &str) -> &'static str {
    let rows = |keep: &dyn Fn(&TechniqueRow) -> bool| -> Vec<&str> {
        TABLE.iter().filter(|r| keep(r)).map(|r| r.name).collect()
    };
    let (what, rows) = match TABLE.iter().find(|r| r.estimator.section() == section) {
        Some(row) => (
            format!("estimator {}", row.estimator.name()),
            rows(&|r| r.estimator == row.estimator),
        ),
        None => match TABLE
            .iter()
            .find(|r| r.source.section() == section && !section.is_empty())
        {
            Some(row) => (
                format!("source {}", row.source.name()),
                rows(&|r| r.source == row.source),
            ),
            None if section == "multiview" => (
                "second view".into(),
                rows(&|r| r.schedule == Schedule::Multiview),
            ),
            None => return "Settings of every technique",
        },
    };
    Box::leak(format!("Settings of the {what} ({})", rows.join(", ")).into_boxed_str())
}

/// The help of `knob`'s primary flag: its help, its older names and its default.
fn help(knob: &Knob) -> String {
    let mut text = knob.help.trim_end_matches('.').to_string();
    if !knob.aliases.is_empty() {
        text.push_str(&format!(" (also {})", knob.aliases.join(", ")));
    }
    if !matches!(knob.kind, Kind::Switch { .. }) {
        text.push_str(&format!(
            " [default: {}]",
            AoSettings::default().shown(knob.path)
        ));
    }
    text
}

impl clap::Args for SettingFlags {
    fn augment_args(mut cmd: Command) -> Command {
        for knob in AoSettings::knobs() {
            for (i, flag) in knob.flags().enumerate() {
                let mut arg = Arg::new(id(flag)).long(id(flag));
                arg = if i == 0 {
                    arg.help(help(knob)).help_heading(heading(knob.section()))
                } else {
                    arg.hide(true)
                        .help(format!("The older name of {}.", knob.flag))
                };
                arg = match knob.kind {
                    Kind::Switch { .. } => arg.action(ArgAction::SetTrue),
                    _ => arg
                        .action(ArgAction::Set)
                        .value_name(value_name(knob))
                        .allow_hyphen_values(true),
                };
                cmd = cmd.arg(arg);
            }
        }
        cmd
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

fn value_name(knob: &Knob) -> &'static str {
    match knob.kind {
        Kind::Choice(_) => "NAME",
        Kind::Number { int: true, .. } | Kind::OneOf(_) => "N",
        _ => "X",
    }
}

impl clap::FromArgMatches for SettingFlags {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let mut given = Vec::new();
        for knob in AoSettings::knobs() {
            for flag in knob.flags() {
                match knob.kind {
                    Kind::Switch { flag_sets } => {
                        if matches.get_flag(id(flag)) {
                            given.push((flag, knob, flag_sets.to_string()));
                        }
                    }
                    _ => {
                        if let Some(text) = matches.get_one::<String>(id(flag)) {
                            given.push((flag, knob, text.clone()));
                        }
                    }
                }
            }
        }
        Ok(SettingFlags(given))
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

/// The flag that sets a settings field: `flag_for_field("vao.radius") == Some("--vao-radius")`.
pub fn flag_for_field(field: &str) -> Option<&'static str> {
    AoSettings::knob(field).map(|k| k.flag)
}

/// A settings error as the CLI says it: an invalid or unsupported field named by `flag` (the
/// one typed) or else by its knob's flag.
pub fn named(e: SettingsError, flag: Option<&str>) -> anyhow::Error {
    let flag = |field: &str| {
        flag.map(str::to_string)
            .or(flag_for_field(field).map(String::from))
    };
    match e {
        SettingsError::Invalid { field, value, rule } => match flag(field) {
            Some(flag) => anyhow!("invalid {flag} {value}: {rule}"),
            None => SettingsError::Invalid { field, value, rule }.into(),
        },
        SettingsError::Unsupported {
            field,
            value,
            adapter,
            reason,
        } => match flag(field) {
            Some(flag) => {
                anyhow!("{flag} {value} is not supported on adapter '{adapter}': {reason}")
            }
            None => SettingsError::Unsupported {
                field,
                value,
                adapter,
                reason,
            }
            .into(),
        },
        e => e.into(),
    }
}

/// Any error on its way to the user: a library settings error (from wherever it came, e.g. the
/// adapter refusing a sample count when the map is made) names the flag instead of the field.
pub fn for_user(e: anyhow::Error) -> anyhow::Error {
    match e.downcast::<obscura::Error>() {
        Ok(obscura::Error::Settings(s)) => named(s, None),
        Ok(other) => other.into(),
        Err(e) => match e.downcast::<SettingsError>() {
            Ok(s) => named(s, None),
            Err(e) => e,
        },
    }
}
