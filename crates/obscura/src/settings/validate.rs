//! [`AoSettings::validate`]: every value no kernel can use is an error naming its field; the
//! field paths those messages use ([`AoSettings::field_paths`]) and the radius of the technique
//! in use ([`AoSettings::radius`]).

use super::*;

pub(super) fn invalid(
    field: &'static str,
    value: impl fmt::Display,
    rule: impl Into<String>,
) -> SettingsError {
    SettingsError::Invalid {
        field,
        value: value.to_string(),
        rule: rule.into(),
    }
}

impl AoSettings {
    /// Reject values no kernel can use; every message names the field (`vao.radius`) and the
    /// valid range. Each field's own range is its knob's (`KNOBS` beside its struct); only the
    /// rules between fields are written here.
    pub fn validate(&self) -> Result<(), SettingsError> {
        self.check_fields()?;
        let h = &self.hbao_plus;
        if h.directions * h.steps > 32 {
            return Err(invalid(
                "hbao_plus.steps",
                h.steps,
                "must be at least 1 with directions × steps ≤ 32 (one bit per sample), e.g. 4",
            ));
        }
        let g = &self.gtao_vb;
        if g.slices * 2 * g.steps > 32 {
            return Err(invalid(
                "gtao_vb.steps",
                g.steps,
                "must be at least 1 with slices × 2 × steps ≤ 32 (one bit per sample), e.g. 2",
            ));
        }
        if self.technique.estimator() == Estimator::Hemisphere
            && self.hemisphere.budgeted()
            && !self.temporal.enabled
        {
            let (field, value) = match self.hemisphere.ray_budget {
                0 => (
                    "hemisphere.time_budget",
                    self.hemisphere.time_budget.to_string(),
                ),
                n => ("hemisphere.ray_budget", n.to_string()),
            };
            return Err(invalid(
                field,
                value,
                "needs temporal accumulation (a pixel granted no rays keeps its history): turn on \
                 temporal.enabled, or set it to 0",
            ));
        }
        let r = &self.ray_sd;
        if r.max_count < r.reservoir {
            return Err(invalid(
                "ray_sd.max_count",
                r.max_count,
                "must be at least ray_sd.reservoir and at most 64, e.g. 8",
            ));
        }
        Ok(())
    }

    /// The world radius R of the technique's estimator (`vao.radius`, `hbao.radius`, …).
    pub fn radius(&self) -> f32 {
        match crate::knob::get(&self.to_tree(), self.radius_field()) {
            Some(crate::knob::Value::Float(r)) => *r as f32,
            _ => unreachable!("every estimator's radius is a number"),
        }
    }

    /// Sets the world radius R of the technique's estimator ([`Self::radius`]), unchecked as a
    /// field assignment is ([`Self::validate`] checks it).
    pub fn set_radius(&mut self, radius: f32) {
        self.set_radius_of(self.technique.estimator(), radius);
    }

    fn set_radius_of(&mut self, estimator: Estimator, radius: f32) {
        let mut tree = self.to_tree();
        let value = crate::knob::Value::Float(f64::from(radius));
        crate::knob::set(&mut tree, estimator.caps().radius, Some(value));
        *self = tree.try_into().expect("settings with a radius read back");
    }

    /// Sets the world radius R of every estimator (`vao.radius`, `hbao.radius`, … all eight),
    /// whichever the technique runs: techniques compared side by side then reach as far, and so
    /// does the ground truth, which takes `vao.radius`. Each estimator still reads R its own way
    /// (docs/SETTINGS.md: e.g. GTAO's samples reach 1.457 R, HBAO+ fades by 1 − d²/R²).
    pub fn set_every_radius(&mut self, radius: f32) {
        for estimator in Estimator::all() {
            self.set_radius_of(estimator, radius);
        }
    }

    /// The settings field that holds [`Self::radius`] (`vao.radius`, `hbao.radius`, …).
    pub fn radius_field(&self) -> &'static str {
        self.technique.estimator().caps().radius
    }

    /// The path of every field, as settings files and [`SettingsError::Invalid`] name them
    /// (`technique`, `vao.radius`, …, `stochastic_depth.mask`), sorted.
    pub fn field_paths() -> Vec<String> {
        fn walk(prefix: &str, value: &serde_json::Value, out: &mut Vec<String>) {
            match value {
                serde_json::Value::Object(map) => {
                    for (key, v) in map {
                        let path = if prefix.is_empty() {
                            key.clone()
                        } else {
                            format!("{prefix}.{key}")
                        };
                        walk(&path, v, out);
                    }
                }
                _ => out.push(prefix.to_string()),
            }
        }
        let mut out = Vec::new();
        walk("", &to_value(&AoSettings::default()), &mut out);
        out
    }
}

pub(super) fn to_value(settings: &AoSettings) -> serde_json::Value {
    serde_json::to_value(settings).expect("AoSettings serialises to JSON")
}
