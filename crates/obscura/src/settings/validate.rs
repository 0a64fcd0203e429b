//! [`AoSettings::validate`]: every value no kernel can use is an error naming its field; the
//! field paths those messages use ([`AoSettings::field_paths`]) and the radius of the technique
//! in use ([`AoSettings::radius`]).

use super::*;

pub(super) fn invalid(
    field: &'static str,
    value: impl fmt::Display,
    rule: &'static str,
) -> SettingsError {
    SettingsError::Invalid {
        field,
        value: value.to_string(),
        rule,
    }
}

impl AoSettings {
    /// Reject values no kernel can use; every message names the field (`vao.radius`) and the
    /// valid range. Every rule is about one field alone.
    pub fn validate(&self) -> Result<(), SettingsError> {
        let v = &self.vao;
        if !(v.radius.is_finite() && v.radius > 0.0) {
            return Err(invalid(
                "vao.radius",
                v.radius,
                "must be a positive number of world units, e.g. 0.5",
            ));
        }
        if !(v.thickness.is_finite() && v.thickness >= 0.0) {
            return Err(invalid(
                "vao.thickness",
                v.thickness,
                "must be zero or positive, e.g. 0.5",
            ));
        }
        if !(v.exponent.is_finite() && v.exponent > 0.0) {
            return Err(invalid(
                "vao.exponent",
                v.exponent,
                "must be positive, e.g. 1.3",
            ));
        }
        if ![8, 16, 32].contains(&v.samples) {
            return Err(invalid("vao.samples", v.samples, "must be 8, 16 or 32"));
        }
        let cap = self.max_radius_px;
        if !(cap == 0.0 || (1.0..=1e6).contains(&cap)) {
            return Err(invalid(
                "max_radius_px",
                cap,
                "must be 0 (no cap) or from 1 to 1e6 pixels, e.g. 512 (seed 002 §3.5)",
            ));
        }
        if !(self.peel_separation.is_finite() && self.peel_separation >= 0.0) {
            return Err(invalid(
                "peel_separation",
                self.peel_separation,
                "must be zero or positive (world units), e.g. 0.01",
            ));
        }
        let sd = &self.stochastic_depth;
        if !SD_SAMPLE_COUNTS.contains(&sd.samples) {
            return Err(invalid(
                "stochastic_depth.samples",
                sd.samples,
                "must be 1, 2, 4, 8 or 16, e.g. 4",
            ));
        }
        if let Some(alpha) = sd.alpha.filter(|a| !(*a > 0.0 && *a <= 1.0)) {
            return Err(invalid(
                "stochastic_depth.alpha",
                alpha,
                "must be in (0, 1], e.g. 0.375, or left out for 1.5/S",
            ));
        }
        self.ray_sd.validate()?;
        let mv = &self.multiview;
        if !(mv.angle.is_finite() && mv.angle > 0.0 && mv.angle <= 60.0) {
            return Err(invalid(
                "multiview.angle",
                mv.angle,
                "must be in (0, 60] degrees, e.g. 30",
            ));
        }
        if let Some(focus) = mv.focus.filter(|f| !(f.is_finite() && *f > 0.0)) {
            return Err(invalid(
                "multiview.focus",
                focus,
                "must be a positive distance in world units, or left out for the scene's centre",
            ));
        }
        if !(sd.compensation.is_finite() && (1.0..=8.0).contains(&sd.compensation)) {
            return Err(invalid(
                "stochastic_depth.compensation",
                sd.compensation,
                "must be in [1, 8]: 1 is off, the paper used 2",
            ));
        }
        if sd.guard_band > MAX_SD_GUARD_BAND {
            return Err(invalid(
                "stochastic_depth.guard_band",
                sd.guard_band,
                "must be at most 2048 pixels (0 is off)",
            ));
        }
        let h = &self.hbao;
        if !(h.radius.is_finite() && h.radius > 0.0) {
            return Err(invalid(
                "hbao.radius",
                h.radius,
                "must be a positive number of world units, e.g. 0.5",
            ));
        }
        if !(h.angle_bias.is_finite() && (0.0..std::f32::consts::FRAC_PI_2).contains(&h.angle_bias))
        {
            return Err(invalid(
                "hbao.angle_bias",
                h.angle_bias,
                "must be in [0, π/2) radians, e.g. 0.1",
            ));
        }
        if !(h.exponent.is_finite() && h.exponent > 0.0) {
            return Err(invalid(
                "hbao.exponent",
                h.exponent,
                "must be positive, e.g. 1",
            ));
        }
        if !(1..=HBAO_MAX_DIRECTIONS).contains(&h.directions) {
            return Err(invalid(
                "hbao.directions",
                h.directions,
                "must be 1 to 64, e.g. 8",
            ));
        }
        if !(1..=128).contains(&h.steps) {
            return Err(invalid("hbao.steps", h.steps, "must be 1 to 128, e.g. 4"));
        }
        let g = &self.gtao;
        if !(g.radius.is_finite() && g.radius > 0.0) {
            return Err(invalid(
                "gtao.radius",
                g.radius,
                "must be a positive number of world units, e.g. 0.5",
            ));
        }
        if !(g.thickness_blend.is_finite() && (0.0..=1.0).contains(&g.thickness_blend)) {
            return Err(invalid(
                "gtao.thickness_blend",
                g.thickness_blend,
                "must be in [0, 1], e.g. 0 (the plain maximum horizon)",
            ));
        }
        if !(g.exponent.is_finite() && g.exponent > 0.0) {
            return Err(invalid(
                "gtao.exponent",
                g.exponent,
                "must be positive, e.g. 1",
            ));
        }
        if !(1..=GTAO_MAX_SLICES).contains(&g.slices) {
            return Err(invalid("gtao.slices", g.slices, "must be 1 to 16, e.g. 2"));
        }
        if !(1..=32).contains(&g.steps) {
            return Err(invalid("gtao.steps", g.steps, "must be 1 to 32, e.g. 2"));
        }
        let py = &self.pyramid;
        if !(1..=8).contains(&py.levels) {
            return Err(invalid(
                "pyramid.levels",
                py.levels,
                "must be 1 to 8, e.g. 5",
            ));
        }
        if !(2..=4).contains(&py.factor) {
            return Err(invalid(
                "pyramid.factor",
                py.factor,
                "must be 2, 3 or 4, e.g. 3",
            ));
        }
        let ph = &self.pyramid_hbao;
        if !(ph.radius.is_finite() && ph.radius > 0.0) {
            return Err(invalid(
                "pyramid_hbao.radius",
                ph.radius,
                "must be a positive number of world units, e.g. 0.5",
            ));
        }
        if !(ph.exponent.is_finite() && ph.exponent > 0.0) {
            return Err(invalid(
                "pyramid_hbao.exponent",
                ph.exponent,
                "must be positive, e.g. 1",
            ));
        }
        if !(1..=32).contains(&ph.directions) {
            return Err(invalid(
                "pyramid_hbao.directions",
                ph.directions,
                "must be 1 to 32, e.g. 8",
            ));
        }
        if !(1..=16).contains(&ph.steps) {
            return Err(invalid(
                "pyramid_hbao.steps",
                ph.steps,
                "must be 1 to 16, e.g. 4",
            ));
        }
        let sao = &self.sao;
        if !(sao.radius.is_finite() && sao.radius > 0.0) {
            return Err(invalid(
                "sao.radius",
                sao.radius,
                "must be a positive number of world units, e.g. 0.5",
            ));
        }
        if !(1..=64).contains(&sao.samples) {
            return Err(invalid(
                "sao.samples",
                sao.samples,
                "must be 1 to 64, e.g. 11",
            ));
        }
        if !(sao.spiral_turns.is_finite() && sao.spiral_turns > 0.0) {
            return Err(invalid(
                "sao.spiral_turns",
                sao.spiral_turns,
                "must be positive, e.g. 7",
            ));
        }
        if !(sao.bias.is_finite() && sao.bias >= 0.0) {
            return Err(invalid(
                "sao.bias",
                sao.bias,
                "must be zero or positive world units, e.g. 0.01",
            ));
        }
        if !(sao.intensity.is_finite() && sao.intensity > 0.0) {
            return Err(invalid(
                "sao.intensity",
                sao.intensity,
                "must be positive, e.g. 1",
            ));
        }
        let ss = &self.ssao;
        if !(ss.radius.is_finite() && ss.radius > 0.0) {
            return Err(invalid(
                "ssao.radius",
                ss.radius,
                "must be a positive number of world units, e.g. 0.5",
            ));
        }
        if !(1..=32).contains(&ss.samples) {
            return Err(invalid(
                "ssao.samples",
                ss.samples,
                "must be 1 to 32 (one bit per sample), e.g. 32",
            ));
        }
        if !(ss.intensity.is_finite() && ss.intensity > 0.0) {
            return Err(invalid(
                "ssao.intensity",
                ss.intensity,
                "must be positive, e.g. 1",
            ));
        }
        if !(ss.bias.is_finite() && ss.bias >= 0.0) {
            return Err(invalid(
                "ssao.bias",
                ss.bias,
                "must be zero or positive, e.g. 0.0001",
            ));
        }
        if !(ss.contrast.is_finite() && ss.contrast > 0.0) {
            return Err(invalid(
                "ssao.contrast",
                ss.contrast,
                "must be positive, e.g. 1",
            ));
        }
        let h = &self.hbao_plus;
        if !(h.radius.is_finite() && h.radius > 0.0) {
            return Err(invalid(
                "hbao_plus.radius",
                h.radius,
                "must be a positive number of world units, e.g. 1.0",
            ));
        }
        if !(h.bias.is_finite() && (0.0..1.0).contains(&h.bias)) {
            return Err(invalid(
                "hbao_plus.bias",
                h.bias,
                "must be in [0, 1), e.g. 0.1",
            ));
        }
        if !(h.exponent.is_finite() && h.exponent > 0.0) {
            return Err(invalid(
                "hbao_plus.exponent",
                h.exponent,
                "must be positive, e.g. 2",
            ));
        }
        if !(1..=32).contains(&h.directions) {
            return Err(invalid(
                "hbao_plus.directions",
                h.directions,
                "must be 1 to 32, e.g. 8",
            ));
        }
        if h.steps == 0 || h.directions * h.steps > 32 {
            return Err(invalid(
                "hbao_plus.steps",
                h.steps,
                "must be at least 1 with directions × steps ≤ 32 (one bit per sample), e.g. 4",
            ));
        }
        let g = &self.gtao_vb;
        if !(g.radius.is_finite() && g.radius > 0.0) {
            return Err(invalid(
                "gtao_vb.radius",
                g.radius,
                "must be a positive number of world units, e.g. 0.5",
            ));
        }
        if !(g.thickness.is_finite() && g.thickness >= 0.0) {
            return Err(invalid(
                "gtao_vb.thickness",
                g.thickness,
                "must be zero or positive world units, e.g. 0.25",
            ));
        }
        if !(g.exponent.is_finite() && g.exponent > 0.0) {
            return Err(invalid(
                "gtao_vb.exponent",
                g.exponent,
                "must be positive, e.g. 1",
            ));
        }
        if !(1..=3).contains(&g.slices) {
            return Err(invalid(
                "gtao_vb.slices",
                g.slices,
                "must be 1, 2 or 3 (one 32-bit mask each), e.g. 2",
            ));
        }
        if g.steps == 0 || g.slices * 2 * g.steps > 32 {
            return Err(invalid(
                "gtao_vb.steps",
                g.steps,
                "must be at least 1 with slices × 2 × steps ≤ 32 (one bit per sample), e.g. 2",
            ));
        }
        let t = &self.temporal;
        if !(1..=255).contains(&t.frames) {
            return Err(invalid(
                "temporal.frames",
                t.frames,
                "must be between 1 and 255, e.g. 16",
            ));
        }
        let min_tolerance = super::MIN_TEMPORAL_DEPTH_TOLERANCE;
        if !(t.depth_tolerance >= min_tolerance && t.depth_tolerance < 1.0) {
            return Err(invalid(
                "temporal.depth_tolerance",
                t.depth_tolerance,
                // The literal is MIN_TEMPORAL_DEPTH_TOLERANCE (settings/tests.rs checks the two agree).
                "must be a fraction of the depth in [0.002, 1) (the history keeps depth to 0.1 %), \
                 e.g. 0.03",
            ));
        }
        if !(t.normal_tolerance_deg > 0.0 && t.normal_tolerance_deg <= 180.0) {
            return Err(invalid(
                "temporal.normal_tolerance_deg",
                t.normal_tolerance_deg,
                "must be degrees in (0, 180], e.g. 30",
            ));
        }
        let b = &self.blur;
        if b.radius == 0 || b.radius > 16 {
            return Err(invalid("blur.radius", b.radius, "must be between 1 and 16"));
        }
        if !(b.sharpness.is_finite() && b.sharpness >= 0.0) {
            return Err(invalid(
                "blur.sharpness",
                b.sharpness,
                "must be zero or positive",
            ));
        }
        if let Some(sigma) = b.sigma.filter(|s| !(s.is_finite() && *s > 0.0)) {
            return Err(invalid(
                "blur.sigma",
                sigma,
                "must be a positive number of pixels, e.g. 1.5, or left out for HBAO+'s weights",
            ));
        }
        Ok(())
    }

    /// The world radius R of the technique's estimator (`vao.radius`, `hbao.radius`, …).
    pub fn radius(&self) -> f32 {
        let mut copy = *self;
        *copy.radius_mut()
    }

    /// [`Self::radius`], to change.
    pub fn radius_mut(&mut self) -> &mut f32 {
        match self.technique.estimator() {
            Estimator::Vao => &mut self.vao.radius,
            Estimator::Hbao => &mut self.hbao.radius,
            Estimator::HbaoPlus => &mut self.hbao_plus.radius,
            Estimator::Gtao => &mut self.gtao.radius,
            Estimator::GtaoVb => &mut self.gtao_vb.radius,
            Estimator::Ssao => &mut self.ssao.radius,
            Estimator::Sao => &mut self.sao.radius,
            Estimator::PyramidHbao => &mut self.pyramid_hbao.radius,
        }
    }

    /// Sets the world radius R of every estimator (`vao.radius`, `hbao.radius`, … all eight),
    /// whichever the technique runs: techniques compared side by side then reach as far, and so
    /// does the ground truth, which takes `vao.radius`. Each estimator still reads R its own way
    /// (docs/SETTINGS.md: e.g. GTAO's samples reach 1.457 R, HBAO+ fades by 1 − d²/R²).
    pub fn set_every_radius(&mut self, radius: f32) {
        for r in [
            &mut self.vao.radius,
            &mut self.hbao.radius,
            &mut self.hbao_plus.radius,
            &mut self.gtao.radius,
            &mut self.gtao_vb.radius,
            &mut self.ssao.radius,
            &mut self.sao.radius,
            &mut self.pyramid_hbao.radius,
        ] {
            *r = radius;
        }
    }

    /// The settings for the same scene in other units: every field in world units
    /// ([`Self::WORLD_UNIT_FIELDS`]: the radii, GTAO-VB's thickness, SAO's bias and intensity, …)
    /// multiplied by `factor` and every one per world unit (`blur.sharpness`) divided by it;
    /// pixels, angles and fractions unchanged. A scene in centimetres with settings made for
    /// metres takes `settings.scaled(100.0)`; every technique then gives the same image
    /// (tests/it/scale_invariance.rs renders them all both ways).
    pub fn scaled(&self, factor: f32) -> Self {
        let mut s = *self;
        for (field, power) in Self::WORLD_UNIT_FIELDS {
            let value = match field {
                "vao.radius" => &mut s.vao.radius,
                "hbao.radius" => &mut s.hbao.radius,
                "hbao_plus.radius" => &mut s.hbao_plus.radius,
                "gtao.radius" => &mut s.gtao.radius,
                "gtao_vb.radius" => &mut s.gtao_vb.radius,
                "gtao_vb.thickness" => &mut s.gtao_vb.thickness,
                "ssao.radius" => &mut s.ssao.radius,
                "sao.radius" => &mut s.sao.radius,
                "sao.bias" => &mut s.sao.bias,
                "sao.intensity" => &mut s.sao.intensity,
                "pyramid_hbao.radius" => &mut s.pyramid_hbao.radius,
                "peel_separation" => &mut s.peel_separation,
                "blur.sharpness" => &mut s.blur.sharpness,
                "multiview.focus" => match &mut s.multiview.focus {
                    Some(focus) => focus,
                    None => continue,
                },
                _ => unreachable!("WORLD_UNIT_FIELDS names {field}, which scaled() lacks"),
            };
            *value *= factor.powi(power);
        }
        s
    }

    /// The fields that depend on the scene's units, with the power of the world unit they carry
    /// (1: a length, −1: per length); docs/SETTINGS.md says "world units" or "per world unit"
    /// for exactly these (tested).
    pub const WORLD_UNIT_FIELDS: [(&'static str, i32); 14] = [
        ("vao.radius", 1),
        ("hbao.radius", 1),
        ("hbao_plus.radius", 1),
        ("gtao.radius", 1),
        ("gtao_vb.radius", 1),
        ("gtao_vb.thickness", 1),
        ("ssao.radius", 1),
        ("sao.radius", 1),
        ("sao.bias", 1),
        ("sao.intensity", 1),
        ("pyramid_hbao.radius", 1),
        ("peel_separation", 1),
        ("multiview.focus", 1),
        ("blur.sharpness", -1),
    ];

    /// The settings field that holds [`Self::radius`] (`vao.radius`, `hbao.radius`, …).
    pub fn radius_field(&self) -> &'static str {
        match self.technique.estimator() {
            Estimator::Vao => "vao.radius",
            Estimator::Hbao => "hbao.radius",
            Estimator::HbaoPlus => "hbao_plus.radius",
            Estimator::Gtao => "gtao.radius",
            Estimator::GtaoVb => "gtao_vb.radius",
            Estimator::Ssao => "ssao.radius",
            Estimator::Sao => "sao.radius",
            Estimator::PyramidHbao => "pyramid_hbao.radius",
        }
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
