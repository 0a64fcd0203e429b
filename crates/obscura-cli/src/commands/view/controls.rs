//! The settings panel's widgets: technique (from the technique table), presets, and the
//! parameters of the technique's estimator, source and filter (from the settings' knobs). They edit a copy of `AoSettings`;
//! the viewer rebuilds the renderer when it differs (a renderer's settings are fixed at creation),
//! and an invalid combination is reported by `Renderer::new`'s validation in the panel, not here.

use eframe::egui;
use obscura::knob::{self, Kind, Knob, Value, Widget};
use obscura::settings::Preset;
use obscura::{AoSettings, Technique};

/// A combo box over every row of the technique table.
pub fn technique_combo(ui: &mut egui::Ui, label: &str, technique: &mut Technique) {
    egui::ComboBox::from_label(label)
        .selected_text(technique.name())
        .height(600.0)
        .show_ui(ui, |ui| {
            for t in Technique::all() {
                ui.selectable_value(technique, t, t.name())
                    .on_hover_text(t.row().summary);
            }
        });
}

/// Preset buttons: the whole settings of the technique at that level, in the scene's units
/// (`units_per_metre`: `--units`, as the command line converted the starting settings).
pub fn presets(ui: &mut egui::Ui, settings: &mut AoSettings, units_per_metre: f32) {
    ui.horizontal(|ui| {
        ui.label("preset");
        for p in Preset::ALL {
            let preset = AoSettings::preset(settings.technique, p).scaled(units_per_metre);
            if ui
                .selectable_label(*settings == preset, p.name())
                .on_hover_text("docs/SETTINGS.md lists what each preset sets")
                .clicked()
            {
                *settings = preset;
            }
        }
    });
}

/// The panel's widgets for `settings.technique`: every knob with a widget (obscura::knob) of
/// the row's estimator and source and of the settings every row has (blur, resolution, radius
/// cap), labelled by its field path, its help on hover. `scene_scale` (the scene's diagonal)
/// scales the sliders of world lengths.
pub fn parameters(ui: &mut egui::Ui, settings: &mut AoSettings, scene_scale: f32) {
    let row = settings.technique.row();
    let sections = ["", "blur", row.estimator.section(), row.source.section()];
    // The values as this frame starts: a widget changes only its own field.
    let tree = settings.to_tree();
    for knob in AoSettings::knobs() {
        if knob.widget != Widget::Hidden && sections.contains(&knob.section()) {
            knob_widget(ui, settings, &tree, knob, scene_scale);
        }
    }
}

fn knob_widget(
    ui: &mut egui::Ui,
    settings: &mut AoSettings,
    tree: &Value,
    knob: &'static Knob,
    scale: f32,
) {
    let Some(value) = knob::get(tree, knob.path).cloned() else {
        return; // an optional field left out: files and flags only
    };
    let mut new = value.clone();
    let response = ui.horizontal(|ui| match (knob.widget, knob.kind) {
        (Widget::Checkbox, _) => {
            if let Value::Boolean(b) = &mut new {
                ui.checkbox(b, knob.path);
            }
        }
        (Widget::Buttons, Kind::OneOf(values)) => {
            ui.label(knob.path);
            for v in values {
                if ui
                    .selectable_label(value.as_integer() == Some(i64::from(*v)), v.to_string())
                    .clicked()
                {
                    new = Value::Integer(i64::from(*v));
                }
            }
        }
        (Widget::Buttons, Kind::Choice(names)) => {
            ui.label(knob.path);
            for name in names {
                if ui
                    .selectable_label(value.as_str() == Some(name), *name)
                    .clicked()
                {
                    new = Value::String(name.to_string());
                }
            }
        }
        (
            widget,
            Kind::Number {
                min,
                max,
                int,
                zero,
                ..
            },
        ) => {
            let (mut lo, mut hi, log) = match widget {
                Widget::Slider { min, max, log } => (min, max, log),
                _ => (min, max, false),
            };
            if knob.scale == 1 {
                let s = f64::from(scale).max(1e-3);
                (lo, hi) = ((lo * s).max(1e-4), hi * s);
            }
            let mut x = value
                .as_float()
                .or(value.as_integer().map(|i| i as f64))
                .unwrap_or(lo);
            let mut slider = egui::Slider::new(&mut x, lo..=hi)
                .logarithmic(log)
                .text(knob.path);
            // Whole numbers, and whole pixels where 0 means off (never in (0, 1)).
            if int || zero.is_some() {
                slider = slider.step_by(1.0);
            }
            ui.add(slider);
            new = if int {
                Value::Integer(x.round() as i64)
            } else {
                Value::Float(x)
            };
        }
        _ => {}
    });
    response.response.on_hover_text(knob.help);
    if new != value {
        // Out of range: the slider springs back (the knob's own check, as flags get).
        let _ = settings.set_field(knob, Some(new));
    }
}
