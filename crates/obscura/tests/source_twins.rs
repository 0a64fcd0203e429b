//! Every dual-depth row gives the same image as its first-layer twin (same estimator and
//! schedule) where nothing is hidden: a height field seen from above has no second layer, so the
//! source has nothing to add. Table-driven: a new estimator's dual row is checked here without an
//! edit. (The stochastic-depth rows are held to the same identity in tests/stochastic_depth.rs.)

mod common;
use common::*;
use glam::Vec3;
use obscura::technique::{Source, TABLE};
use obscura::{AoSettings, Renderer};

#[test]
fn every_dual_depth_row_equals_its_first_layer_twin_with_one_layer() {
    let gpu = gpu();
    let scene = height_field();
    let mut cam = camera(Vec3::new(0.0, 7.0, 0.0), Vec3::ZERO, 30.0);
    cam.up = Vec3::NEG_Z;
    let rows: Vec<_> = TABLE
        .iter()
        .filter(|r| r.source == Source::DualDepth)
        .collect();
    assert!(!rows.is_empty());
    for row in rows {
        let twin = TABLE
            .iter()
            .find(|t| {
                t.source == Source::FirstLayer
                    && t.estimator == row.estimator
                    && t.schedule == row.schedule
            })
            .unwrap_or_else(|| panic!("{}: no first-layer twin", row.name));
        let render = |technique| {
            let mut s = AoSettings {
                technique,
                ..AoSettings::default()
            };
            s.blur.enabled = false;
            let mut r = Renderer::new(&gpu, &scene, &s, 96, 64, 16).unwrap();
            r.render(&cam, None).unwrap();
            r.read_ao().unwrap()
        };
        let (single, dual) = (render(twin.technique), render(row.technique));
        let worst = single
            .iter()
            .zip(&dual)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f32, f32::max);
        println!("max |{} − {}| {worst:e}", twin.name, row.name);
        assert!(worst <= 1e-6, "max |{} − {}| {worst}", twin.name, row.name);
        assert!(
            single.iter().any(|&v| v < 0.95),
            "{}: the view must have occlusion",
            twin.name
        );
    }
}
