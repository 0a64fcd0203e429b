//! A setting declared once: a [`Knob`] states a settings field's path, its valid values, its unit
//! (the power of the world unit it carries), its command-line flag and aliases, its help, its
//! viewer widget. Each settings struct lists its knobs beside its fields (`KNOBS`), and everything
//! else derives from those lists: validation (`AoSettings::validate`; only rules between fields
//! stay hand-written), `AoSettings::scaled`, the CLI's setting flags and the flag names in its
//! errors, the viewer's sliders and docs/SETTINGS.md's field table.
//!
//! Knobs are plain data (`const`) and reach their field through the settings' serde form (the
//! same paths as settings files, as a [`Value`] tree): no accessor is written per field, so a
//! field and its knob are two declarations in one file. The cost, a settings value's round trip
//! through that tree, is paid only when settings are made or changed, never per frame of GPU
//! work. A declarative list over a derive: a derive macro needs a proc-macro crate of its own, and
//! the declarations read as well as a table (docs/ARCHITECTURE.md, "Settings").

use std::fmt::Write as _;

/// A settings value in serde form. TOML's, not JSON's: it keeps NaN and infinities, which a
/// settings field may hold and validation must see.
pub use toml::Value;

/// One settings field, declared once (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Knob {
    /// The field's path in settings files and errors: `gtao.slices`.
    pub path: &'static str,
    /// The command-line flag: `--gtao-slices`.
    pub flag: &'static str,
    /// Older names of the flag, still accepted: `--hbao-radius` for `--hbao-plus-radius`.
    pub aliases: &'static [&'static str],
    /// One line for `--help` and the viewer.
    pub help: &'static str,
    /// docs/SETTINGS.md's description where it says more than `help` (empty: `help`).
    pub doc: &'static str,
    /// The values it takes.
    pub kind: Kind,
    /// The power of the world unit it carries: 1 a length, −1 per length, 0 none
    /// (`AoSettings::scaled` multiplies by the factor to this power).
    pub scale: i32,
    /// The unit's name where `scale` is 0 (`pixels`, `degrees`, `units of R`; empty: none).
    pub units: &'static str,
    /// `Some(what)`: the field is optional; left out (or `auto` on the command line) it does
    /// `what` ("1.5/S").
    pub auto: Option<&'static str>,
    /// Added to the valid range in errors and docs: "(one bit per sample)".
    pub note: &'static str,
    /// How the viewer shows it.
    pub widget: Widget,
}

/// The values a [`Knob`] takes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// A finite number between two bounds, each closed or open (`f64::INFINITY`: unbounded);
    /// `int`: whole numbers only; `zero`: 0 is also valid, meaning this ("no cap").
    Number {
        /// The lower bound.
        min: f64,
        /// The upper bound (`f64::INFINITY`: none).
        max: f64,
        /// Whether `min` itself is excluded.
        min_open: bool,
        /// Whether `max` itself is excluded.
        max_open: bool,
        /// Whole numbers only.
        int: bool,
        /// 0 is valid too, meaning this.
        zero: Option<&'static str>,
    },
    /// One of these whole numbers.
    OneOf(&'static [u32]),
    /// One of these names (the field's serde strings).
    Choice(&'static [&'static str]),
    /// true or false; the flag takes no value and sets `flag_sets`.
    Switch {
        /// The value the flag sets (`--no-blur` sets `blur.enabled` false).
        flag_sets: bool,
    },
}

/// How the viewer shows a [`Knob`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Widget {
    /// Not in the viewer's panel (settings files and flags only).
    Hidden,
    /// A slider over the knob's range, or over `[min, max]` where given (× the scene's size for
    /// world lengths), logarithmic where `log`.
    Slider {
        /// The slider's left end.
        min: f64,
        /// The slider's right end.
        max: f64,
        /// Logarithmic.
        log: bool,
    },
    /// A slider over the knob's whole range.
    Range,
    /// One button per value (`OneOf`, `Choice`).
    Buttons,
    /// A check box (`Switch`).
    Checkbox,
}

impl Widget {
    /// An estimator's radius: a logarithmic slider from 1/1000 of the scene's size to all of it.
    pub const RADIUS: Widget = Widget::Slider {
        min: 1e-3,
        max: 1.0,
        log: true,
    };
}

impl Kind {
    /// A finite number > 0.
    pub const POSITIVE: Kind = Kind::number(0.0, f64::INFINITY, true, false);
    /// A finite number ≥ 0.
    pub const NON_NEGATIVE: Kind = Kind::number(0.0, f64::INFINITY, false, false);

    /// A finite number in `[min, max]`, each end open where asked.
    pub const fn number(min: f64, max: f64, min_open: bool, max_open: bool) -> Kind {
        Kind::Number {
            min,
            max,
            min_open,
            max_open,
            int: false,
            zero: None,
        }
    }

    /// This kind where also 0 is valid, meaning `what` ("no cap").
    pub const fn or_zero(self, what: &'static str) -> Kind {
        match self {
            Kind::Number {
                min,
                max,
                min_open,
                max_open,
                int,
                ..
            } => Kind::Number {
                min,
                max,
                min_open,
                max_open,
                int,
                zero: Some(what),
            },
            other => other,
        }
    }

    /// A whole number in `[min, max]`.
    pub const fn int(min: u32, max: u32) -> Kind {
        Kind::Number {
            min: min as f64,
            max: max as f64,
            min_open: false,
            max_open: false,
            int: true,
            zero: None,
        }
    }
}

impl Knob {
    /// A knob with no aliases, no unit, not optional, hidden from the viewer: the builder
    /// methods below add the rest.
    pub const fn new(
        path: &'static str,
        flag: &'static str,
        help: &'static str,
        kind: Kind,
    ) -> Knob {
        Knob {
            path,
            flag,
            aliases: &[],
            help,
            doc: "",
            kind,
            scale: 0,
            units: "",
            auto: None,
            note: "",
            widget: Widget::Hidden,
        }
    }

    /// Older flag names, still accepted.
    pub const fn aliases(mut self, aliases: &'static [&'static str]) -> Knob {
        self.aliases = aliases;
        self
    }

    /// A length in world units.
    pub const fn length(mut self) -> Knob {
        self.scale = 1;
        self
    }

    /// A quantity per world unit.
    pub const fn per_length(mut self) -> Knob {
        self.scale = -1;
        self
    }

    /// The unit's name (`pixels`, `degrees`) of a quantity that does not scale with the scene.
    pub const fn units(mut self, units: &'static str) -> Knob {
        self.units = units;
        self
    }

    /// docs/SETTINGS.md's description, where it says more than the help.
    pub const fn doc(mut self, doc: &'static str) -> Knob {
        self.doc = doc;
        self
    }

    /// An optional field: left out, it does `what`.
    pub const fn auto(mut self, what: &'static str) -> Knob {
        self.auto = Some(what);
        self
    }

    /// Words added to the valid range in errors and docs.
    pub const fn note(mut self, note: &'static str) -> Knob {
        self.note = note;
        self
    }

    /// How the viewer shows it.
    pub const fn widget(mut self, widget: Widget) -> Knob {
        self.widget = widget;
        self
    }

    /// The settings section it belongs to: `gtao` for `gtao.slices`, empty at the top level.
    pub fn section(&self) -> &'static str {
        self.path.rsplit_once('.').map_or("", |(s, _)| s)
    }

    /// The field's name within its section: `slices`.
    pub fn name(&self) -> &'static str {
        self.path.rsplit_once('.').map_or(self.path, |(_, n)| n)
    }

    /// The unit as docs and errors say it: `world units`, `per world unit`, `pixels`, or empty.
    pub fn unit_text(&self) -> &'static str {
        match self.scale {
            1 => "world units",
            -1 => "per world unit",
            _ => self.units,
        }
    }

    /// Every flag that sets it, the primary first.
    pub fn flags(&self) -> impl Iterator<Item = &'static str> {
        std::iter::once(self.flag).chain(self.aliases.iter().copied())
    }

    /// The valid values in words, as docs/SETTINGS.md's table gives them: `1 to 16`,
    /// `> 0, world units`, `"clipped" or "hemisphere"`.
    pub fn values_text(&self) -> String {
        let mut text = self.range_text(true);
        if let Some(what) = self.auto {
            let _ = write!(text, ", or left out / `auto` for {what}");
        }
        text
    }

    /// What a valid value is, with `example` (the default), for errors: "must be 1 to 16, e.g. 2".
    pub fn rule(&self, example: &str) -> String {
        let mut rule = format!("must be {}", self.range_text(false));
        if !self.note.is_empty() {
            let _ = write!(rule, " ({})", self.note);
        }
        if !example.is_empty() {
            let _ = write!(rule, ", e.g. {example}");
        }
        if let Some(what) = self.auto {
            let _ = write!(rule, ", or left out (auto) for {what}");
        }
        rule
    }

    fn range_text(&self, table: bool) -> String {
        let unit = self.unit_text();
        let with_unit = |s: String| {
            if unit.is_empty() {
                s
            } else {
                format!("{s} {unit}")
            }
        };
        match self.kind {
            Kind::Number {
                min,
                max,
                min_open,
                max_open,
                int,
                zero,
            } => {
                let body = if max.is_infinite() && min == 0.0 {
                    match (min_open, table) {
                        (true, true) => "> 0".to_string(),
                        (false, true) => "≥ 0".to_string(),
                        (true, false) if !unit.is_empty() => "a positive number of".to_string(),
                        (true, false) => "positive".to_string(),
                        (false, false) => "zero or positive".to_string(),
                    }
                } else if max.is_infinite() {
                    format!("{} {}", if min_open { ">" } else { "≥" }, number(min))
                } else if int && table {
                    format!("{} to {}", number(min), number(max))
                } else if int {
                    format!("between {} and {}", number(min), number(max))
                } else {
                    format!(
                        "in {}{}, {}{}",
                        if min_open { "(" } else { "[" },
                        number(min),
                        number(max),
                        if max_open { ")" } else { "]" }
                    )
                };
                let body = match (table, unit.is_empty()) {
                    (true, false) => format!("{body}, {unit}"),
                    _ => with_unit(body),
                };
                match zero {
                    Some(meaning) => format!("0 ({meaning}) or {body}"),
                    None => body,
                }
            }
            Kind::OneOf(values) => {
                let list: Vec<String> = values.iter().map(|v| v.to_string()).collect();
                with_unit(or_list(&list))
            }
            Kind::Choice(names) => {
                let list: Vec<String> = names.iter().map(|n| format!("'{n}'")).collect();
                or_list(&list)
            }
            Kind::Switch { .. } => "true or false".to_string(),
        }
    }

    /// Whether `value` (the field's serde form; `None`: left out) is valid.
    pub fn accepts(&self, value: Option<&Value>) -> bool {
        let Some(value) = value else {
            return self.auto.is_some();
        };
        match self.kind {
            Kind::Number {
                min,
                max,
                min_open,
                max_open,
                int,
                zero,
            } => {
                let x = match value {
                    Value::Integer(i) => *i as f64,
                    Value::Float(x) => *x,
                    _ => return false,
                };
                if zero.is_some() && x == 0.0 {
                    return true;
                }
                let above = if min_open { x > min } else { x >= min };
                let below = if max_open { x < max } else { x <= max };
                x.is_finite() && above && below && (!int || x.fract() == 0.0)
            }
            Kind::OneOf(values) => value
                .as_integer()
                .is_some_and(|v| values.iter().any(|&a| i64::from(a) == v)),
            Kind::Choice(names) => value.as_str().is_some_and(|s| names.contains(&s)),
            Kind::Switch { .. } => value.is_bool(),
        }
    }

    /// A value as typed on the command line, in the field's serde form: a number, a name
    /// (lowercased; whether it names a value is checked as the settings are read back), or
    /// `Some(None)` for `auto` (an optional field left out). `None` where it is not even of the
    /// right type (the caller reports it with [`Knob::rule`]).
    pub fn parse(&self, text: &str) -> Option<Option<Value>> {
        let text = text.trim();
        if self.auto.is_some() && text.eq_ignore_ascii_case("auto") {
            return Some(None);
        }
        let value = match self.kind {
            Kind::Number { int: true, .. } | Kind::OneOf(_) => {
                Value::Integer(i64::from(text.parse::<u32>().ok()?))
            }
            // Through f32, the fields' type, so that the value is the one a file would give.
            Kind::Number { .. } => Value::Float(f64::from(text.parse::<f32>().ok()?)),
            // Checked when the settings are read back (serde knows the names and their aliases).
            Kind::Choice(_) => Value::String(text.to_ascii_lowercase()),
            Kind::Switch { .. } => Value::Boolean(text.parse::<bool>().ok()?),
        };
        Some(Some(value))
    }
}

/// A value as docs and errors print it: whole numbers without a fraction, others as f32 prints
/// them (so 1.3 reads 1.3).
pub fn number(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else {
        format!("{}", x as f32)
    }
}

/// A value in the field's serde form as a user reads it: numbers by [`number`], names bare,
/// `auto` for an optional field left out.
pub fn show(value: Option<&Value>) -> String {
    match value {
        None => "auto".into(),
        Some(Value::String(s)) => s.clone(),
        Some(Value::Integer(i)) => i.to_string(),
        Some(Value::Float(x)) if x.is_nan() => "NaN".into(),
        Some(Value::Float(x)) => number(*x),
        Some(other) => other.to_string(),
    }
}

/// "a, b or c".
fn or_list(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

/// The value at `path` (`gtao.slices`) of settings in serde form; `None` where left out.
pub fn get<'a>(root: &'a Value, path: &str) -> Option<&'a Value> {
    path.split('.').try_fold(root, |v, key| v.get(key))
}

/// Sets (`Some`) or leaves out (`None`) the value at `path`; `false` where its section does not
/// exist.
pub fn set(root: &mut Value, path: &str, value: Option<Value>) -> bool {
    let (section, name) = match path.rsplit_once('.') {
        Some((section, name)) => (get_mut(root, section), name),
        None => (Some(root), path),
    };
    let Some(Value::Table(table)) = section else {
        return false;
    };
    match value {
        Some(v) => {
            table.insert(name.to_string(), v);
        }
        None => {
            table.remove(name);
        }
    }
    true
}

fn get_mut<'a>(root: &'a mut Value, path: &str) -> Option<&'a mut Value> {
    path.split('.').try_fold(root, |v, key| v.get_mut(key))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_state_the_range_and_the_example() {
        let k = Knob::new("a.radius", "--a-radius", "", Kind::POSITIVE).length();
        assert_eq!(
            k.rule("0.5"),
            "must be a positive number of world units, e.g. 0.5"
        );
        assert_eq!(k.values_text(), "> 0, world units");
        let k = Knob::new("a.slices", "--a-slices", "", Kind::int(1, 16));
        assert_eq!(k.rule("2"), "must be between 1 and 16, e.g. 2");
        assert_eq!(k.values_text(), "1 to 16");
        let k = Knob::new("a.b", "--a-b", "", Kind::number(0.0, 1.0, false, true));
        assert_eq!(k.rule("0.1"), "must be in [0, 1), e.g. 0.1");
        let k = Knob::new("a.n", "--a-n", "", Kind::OneOf(&[8, 16, 32]));
        assert_eq!(k.rule(""), "must be 8, 16 or 32");
        let k = Knob::new("a.c", "--a-c", "", Kind::Choice(&["x", "y"]));
        assert_eq!(k.rule("x"), "must be 'x' or 'y', e.g. x");
    }

    #[test]
    fn values_are_checked_against_the_kind() {
        let k = Knob::new("a.b", "--a-b", "", Kind::number(0.0, 1.0, true, false));
        for (v, ok) in [
            (0.0, false),
            (0.5, true),
            (1.0, true),
            (1.5, false),
            (f64::NAN, false),
        ] {
            assert_eq!(k.accepts(Some(&Value::Float(v))), ok, "{v}");
        }
        assert!(!k.accepts(None));
        assert!(k.auto("x").accepts(None));
        let zero = Kind::number(1.0, 1e6, false, false).or_zero("off");
        let k = Knob::new("a.cap", "--a-cap", "", zero);
        let f = |x: f64| Some(Value::Float(x));
        assert!(k.accepts(f(0.0).as_ref()) && !k.accepts(f(0.5).as_ref()));
        assert!(k.accepts(f(2.0).as_ref()));
        let k = Knob::new("a.n", "--a-n", "", Kind::int(1, 4));
        let i = |x: i64| Some(Value::Integer(x));
        assert!(k.accepts(i(4).as_ref()) && !k.accepts(i(5).as_ref()) && !k.accepts(i(0).as_ref()));
    }

    #[test]
    fn parse_and_paths() {
        let k = Knob::new("a.c", "--a-c", "", Kind::Choice(&["clipped", "hemisphere"]));
        assert_eq!(
            k.parse("Clipped"),
            Some(Some(Value::String("clipped".into())))
        );
        let k = Knob::new("a.x", "--a-x", "", Kind::POSITIVE).auto("1.5/S");
        assert_eq!(k.parse("auto"), Some(None));
        assert_eq!(k.parse("0.1"), Some(Some(Value::Float(f64::from(0.1f32)))));
        assert_eq!(k.parse("abc"), None);
        let mut v: Value = toml::from_str("[a]\nx = 1\n").unwrap();
        assert!(set(&mut v, "a.x", Some(Value::Integer(2))));
        assert!(!set(&mut v, "b.y", Some(Value::Integer(2))));
        assert_eq!(get(&v, "a.x"), Some(&Value::Integer(2)));
        assert!(set(&mut v, "a.x", None));
        assert_eq!(get(&v, "a.x"), None);
    }
}
