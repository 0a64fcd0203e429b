//! What the knobs ([`crate::knob`]) give the settings: every field's check, `scaled`, setting a
//! field by path or by flag (the CLI, the viewer), and docs/SETTINGS.md's field table. Nothing
//! here names a field: they all come from the `KNOBS` lists beside the settings structs.

use super::*;
use crate::estimators::SourceInputs;
use crate::knob::{self, Kind, Knob, Value};

/// The knobs of the settings every technique has and of the sources, in docs/SETTINGS.md's
/// order; each estimator's come from its module (`EstimatorCaps::module`), after these.
const KNOB_LISTS: &[&[Knob]] = &[
    BlurSettings::KNOBS,
    DenoiseSettings::KNOBS,
    AoSettings::KNOBS,
    MultiviewSettings::KNOBS,
    TemporalSettings::KNOBS,
    StochasticDepthSettings::KNOBS,
    RaySdSettings::KNOBS,
    PyramidSettings::KNOBS,
];

impl AoSettings {
    /// Every settings field's knob (all but `technique`), in docs/SETTINGS.md's order.
    pub fn knobs() -> impl Iterator<Item = &'static Knob> {
        let estimators = Estimator::all().into_iter().map(|e| e.caps().module.knobs);
        KNOB_LISTS.iter().copied().chain(estimators).flatten()
    }

    /// What the estimator's parameters read: its settings section (serde form) and its
    /// source's choices.
    pub fn estimator_inputs(&self) -> (Value, SourceInputs) {
        let tree = self.to_tree();
        let section = knob::get(&tree, self.technique.estimator().section())
            .cloned()
            .expect("every estimator has its settings section");
        let sd = &self.stochastic_depth;
        let inputs = SourceInputs {
            literal_query: sd.query == SdQuery::FirstLayer,
            compensation: sd.compensation,
            pyramid_levels: self.pyramid.levels,
            pyramid_factor: self.pyramid.factor,
            ray_budget: self.ray_budget_active(),
        };
        (section, inputs)
    }

    /// Whether the hemisphere rows run under a ray budget: one asked for
    /// (`hemisphere.ray_budget` or `hemisphere.time_budget`) on a hemisphere row with the
    /// temporal accumulation it needs ([`Self::validate`] refuses a budget without it).
    pub fn ray_budget_active(&self) -> bool {
        self.technique.estimator() == crate::technique::Estimator::Hemisphere
            && self.temporal.enabled
            && self.hemisphere.budgeted()
    }

    /// Samples per pixel of the technique's estimator: its `SAMPLE_COUNT` constant, the bits of
    /// a two-phase schedule's mask it uses (e.g. to normalise `render --debug-out`'s
    /// `samples.png`).
    pub fn samples_per_pixel(&self) -> u32 {
        let (section, inputs) = self.estimator_inputs();
        (self.technique.estimator().caps().module.params)(&section, &inputs).1[0] as u32
    }

    /// The knob of the field at `path` (`gtao.slices`).
    pub fn knob(path: &str) -> Option<&'static Knob> {
        Self::knobs().find(|k| k.path == path)
    }

    /// The knob a command-line flag sets, by its name or an alias (`--radius`, `--vao-radius`).
    pub fn knob_for_flag(flag: &str) -> Option<&'static Knob> {
        Self::knobs().find(|k| k.flags().any(|f| f == flag))
    }

    /// These settings in serde form, the form knobs read and write.
    pub fn to_tree(&self) -> Value {
        Value::try_from(self).expect("AoSettings serialises to TOML values")
    }

    /// The value of the field at `path` as a user reads it (`0.5`, `clipped`, `auto`).
    pub fn shown(&self, path: &str) -> String {
        knob::show(knob::get(&self.to_tree(), path))
    }

    /// The field's default as an example for its rule ("" for an optional field left out).
    fn example(knob: &Knob) -> String {
        match knob::get(&AoSettings::default().to_tree(), knob.path) {
            Some(v) => knob::show(Some(v)),
            None => String::new(),
        }
    }

    /// The error for a value `knob` does not take.
    fn rejected(knob: &Knob, value: String) -> SettingsError {
        SettingsError::Invalid {
            field: knob.path,
            value,
            rule: knob.rule(&Self::example(knob)),
        }
    }

    /// Sets the field of `knob` (`None`: left out, for an optional field), checked against its
    /// knob; on an error nothing changes.
    pub fn set_field(
        &mut self,
        knob: &'static Knob,
        value: Option<Value>,
    ) -> Result<(), SettingsError> {
        if !knob.accepts(value.as_ref()) {
            return Err(Self::rejected(knob, knob::show(value.as_ref())));
        }
        let mut tree = self.to_tree();
        let shown = knob::show(value.as_ref());
        if !knob::set(&mut tree, knob.path, value) {
            unreachable!("knob {} names no settings field", knob.path);
        }
        *self = tree.try_into().map_err(|_| Self::rejected(knob, shown))?;
        Ok(())
    }

    /// Sets the field of `knob` from text as typed on the command line (`0.5`, `clipped`,
    /// `auto`); a switch's flag passes "true" or "false".
    pub fn set_field_text(&mut self, knob: &'static Knob, text: &str) -> Result<(), SettingsError> {
        match knob.parse(text) {
            Some(value) => self.set_field(knob, value),
            None => Err(Self::rejected(knob, text.to_string())),
        }
    }

    /// Every field's own rule (its knob's kind), first failure first.
    pub(super) fn check_fields(&self) -> Result<(), SettingsError> {
        let tree = self.to_tree();
        for knob in Self::knobs() {
            let value = knob::get(&tree, knob.path);
            if !knob.accepts(value) {
                return Err(Self::rejected(knob, knob::show(value)));
            }
        }
        Ok(())
    }

    /// The settings for the same scene in other units: every field in world units (a knob's
    /// `scale` 1: the radii, GTAO-VB's thickness, SAO's bias, …) multiplied by
    /// `factor` and every one per world unit (`blur.sharpness`) divided by it; pixels, angles
    /// and fractions unchanged. A scene in centimetres with settings made for metres takes
    /// `settings.scaled(100.0)`; every technique then gives the same image
    /// (tests/it/scale_invariance.rs renders them all both ways).
    pub fn scaled(&self, factor: f32) -> Self {
        let mut tree = self.to_tree();
        for (path, power) in Self::world_unit_fields() {
            if let Some(Value::Float(x)) = knob::get(&tree, path) {
                // In f32, the fields' type, as a caller multiplying the field would.
                let scaled = *x as f32 * factor.powi(power);
                knob::set(&mut tree, path, Some(Value::Float(f64::from(scaled))));
            }
        }
        tree.try_into().expect("scaled settings read back")
    }

    /// The fields that depend on the scene's units, with the power of the world unit they carry
    /// (1: a length, −1: per length): the knobs whose `scale` is not 0. docs/SETTINGS.md says
    /// "world units" or "per world unit" for exactly these.
    pub fn world_unit_fields() -> Vec<(&'static str, i32)> {
        Self::knobs()
            .filter(|k| k.scale != 0)
            .map(|k| (k.path, k.scale))
            .collect()
    }

    /// docs/SETTINGS.md's table of fields: field, flag (and its older names), values, what.
    pub fn fields_markdown() -> String {
        let mut out = String::from(
            "| field | flag | values | what |\n|---|---|---|---|\n| `technique` | `--technique`, \
             `--techniques` | a technique name (`vao`, `sd-svao`, …; README) | the technique |\n",
        );
        for k in Self::knobs() {
            let mut flag = format!("`{}`", k.flag);
            if let Kind::Switch { flag_sets } = k.kind {
                flag.push_str(&format!(" (sets {flag_sets})"));
            }
            for alias in k.aliases {
                flag.push_str(&format!(", `{alias}`"));
            }
            let values = match k.kind {
                Kind::Choice(names) => {
                    let quoted: Vec<String> = names.iter().map(|n| format!("`\"{n}\"`")).collect();
                    match quoted.as_slice() {
                        [init @ .., last] if !init.is_empty() => {
                            format!("{} or {last}", init.join(", "))
                        }
                        _ => quoted.concat(),
                    }
                }
                _ => k.values_text(),
            };
            let mut what = if k.doc.is_empty() { k.help } else { k.doc }.to_string();
            while what.ends_with('.') {
                what.pop();
            }
            if !k.note.is_empty() {
                what.push_str(&format!(" ({})", k.note));
            }
            out.push_str(&format!(
                "| `{}` | {flag} | {values} | {} |\n",
                k.path,
                what.replace('|', "\\|")
            ));
        }
        out
    }
}
