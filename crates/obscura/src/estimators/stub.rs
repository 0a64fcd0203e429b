//! A test-only estimator: an entry of the registry (`registry!`) and a caps literal, nothing
//! else, so that settings/tests.rs can show what an entry alone gives an estimator: its fields'
//! flags, checks, presets, viewer widgets and docs rows. It runs SSAO's WGSL (no row of the
//! technique table uses it, so no pass is ever made of it).

use crate::knob::{Kind, Knob, Widget};
use serde::{Deserialize, Serialize};

/// The stub's settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StubSettings {
    /// A radius in world units.
    pub radius: f32,
    /// A sample count.
    pub samples: u32,
}

impl Default for StubSettings {
    fn default() -> Self {
        Self {
            radius: 0.5,
            samples: 8,
        }
    }
}

impl StubSettings {
    /// Every field's knob (crate::knob).
    pub const KNOBS: &'static [Knob] = &[
        Knob::new("stub.radius", "--stub-radius", "Stub radius R.", Kind::POSITIVE)
            .length()
            .widget(Widget::RADIUS),
        Knob::new("stub.samples", "--stub-samples", "Stub samples.", Kind::int(1, 32))
            .widget(Widget::Range),
    ];
}

/// The stub as the technique table would run it.
pub const MODULE: super::EstimatorModule = super::EstimatorModule {
    wgsl: super::ssao::MODULE.wgsl,
    constants: super::ssao::MODULE.constants,
    knobs: StubSettings::KNOBS,
    params: |section, _| {
        let s: StubSettings = super::section(section);
        (s.radius.to_le_bytes().to_vec(), vec![f64::from(s.samples)])
    },
    table: None,
};
