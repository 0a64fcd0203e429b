//! The settings panel's widgets: technique (from the technique table), presets, and the main
//! parameters of the technique's estimator, source and filter. They edit a copy of `AoSettings`;
//! the viewer rebuilds the renderer when it differs (a renderer's settings are fixed at creation),
//! and an invalid combination is reported by `Renderer::new`'s validation in the panel, not here.

use eframe::egui;
use obscura::settings::{Preset, Resolution, SdRasterizer, SD_SAMPLE_COUNTS};
use obscura::technique::{Estimator, Source};
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

fn radius(ui: &mut egui::Ui, r: &mut f32, scale: f32) {
    ui.add(
        egui::Slider::new(r, (scale * 1e-3).max(1e-4)..=scale.max(1e-3))
            .logarithmic(true)
            .text("radius"),
    );
}

fn count(ui: &mut egui::Ui, v: &mut u32, range: std::ops::RangeInclusive<u32>, text: &str) {
    ui.add(egui::Slider::new(v, range).text(text));
}

/// The main parameters of `settings.technique`; `scene_scale` bounds the radius sliders (the
/// scene's diagonal).
pub fn parameters(ui: &mut egui::Ui, settings: &mut AoSettings, scene_scale: f32) {
    let row = settings.technique.row();
    radius(ui, settings.radius_mut(), scene_scale);
    // Seed 002 §3.5's cap on the radius in pixels; whole pixels, so never in (0, 1).
    ui.add(
        egui::Slider::new(&mut settings.max_radius_px, 0.0..=2048.0)
            .step_by(1.0)
            .text("max radius px (0: none)"),
    );
    match row.estimator {
        Estimator::Vao => {
            let v = &mut settings.vao;
            ui.horizontal(|ui| {
                ui.label("samples");
                for n in [8, 16, 32] {
                    ui.selectable_value(&mut v.samples, n, n.to_string());
                }
            });
            ui.add(egui::Slider::new(&mut v.thickness, 0.0..=2.0).text("thickness τ"));
        }
        Estimator::Hbao => {
            let h = &mut settings.hbao;
            count(ui, &mut h.directions, 1..=64, "directions");
            count(ui, &mut h.steps, 1..=128, "steps");
        }
        Estimator::HbaoPlus => {
            let h = &mut settings.hbao_plus;
            count(ui, &mut h.directions, 1..=32, "directions");
            count(ui, &mut h.steps, 1..=32, "steps (directions × steps ≤ 32)");
        }
        Estimator::Gtao => {
            let g = &mut settings.gtao;
            count(ui, &mut g.slices, 1..=16, "slices");
            count(ui, &mut g.steps, 1..=32, "steps");
        }
        Estimator::Ssao => {
            let s = &mut settings.ssao;
            count(ui, &mut s.samples, 1..=32, "samples");
        }
        Estimator::Sao => {
            let s = &mut settings.sao;
            count(ui, &mut s.samples, 1..=64, "taps");
        }
        Estimator::PyramidHbao => {
            let p = &mut settings.pyramid_hbao;
            count(ui, &mut p.directions, 1..=32, "directions");
            count(ui, &mut p.steps, 1..=16, "steps");
        }
        Estimator::GtaoVb => {
            let g = &mut settings.gtao_vb;
            count(ui, &mut g.slices, 1..=3, "slices");
            count(ui, &mut g.steps, 1..=16, "steps (slices × 2 × steps ≤ 32)");
            ui.add(
                egui::Slider::new(&mut g.thickness, 0.0..=scene_scale.max(1e-3)).text("thickness"),
            );
        }
    }
    match row.source {
        Source::StochasticDepth => {
            let sd = &mut settings.stochastic_depth;
            ui.horizontal(|ui| {
                ui.label("S (samples of the map)");
                for n in SD_SAMPLE_COUNTS {
                    ui.selectable_value(&mut sd.samples, n, n.to_string());
                }
            });
            ui.add(egui::Slider::new(&mut sd.compensation, 1.0..=8.0).text("compensation"));
            ui.horizontal(|ui| {
                ui.label("map rasteriser");
                for r in [
                    SdRasterizer::Auto,
                    SdRasterizer::Hardware,
                    SdRasterizer::Compute,
                ] {
                    ui.selectable_value(&mut sd.rasterizer, r, r.to_string());
                }
            });
        }
        Source::RayStochasticDepth => {
            let r = &mut settings.ray_sd;
            count(ui, &mut r.reservoir, 1..=8, "reservoir N");
            ui.horizontal(|ui| {
                ui.label("map resolution 1/");
                for n in [1, 2, 4] {
                    ui.selectable_value(&mut r.resolution, n, n.to_string());
                }
            });
        }
        _ => {}
    }
    let b = &mut settings.blur;
    ui.checkbox(&mut b.enabled, "bilateral blur");
    if b.enabled {
        count(ui, &mut b.radius, 1..=16, "blur radius");
    }
    ui.horizontal(|ui| {
        ui.label("resolution");
        ui.selectable_value(&mut settings.resolution, Resolution::Full, "full");
        ui.selectable_value(&mut settings.resolution, Resolution::Half, "half");
    });
}
