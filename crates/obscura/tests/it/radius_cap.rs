//! The AO radius's cap on screen (`max_radius_px`; seed 002 §3.5): a shading point whose radius
//! would cover more pixels runs with the radius that covers exactly the cap. On a wall facing
//! the camera every pixel has the same depth, so there a capped radius R equals the uncapped
//! radius R' = cap / (pixels per unit at that depth), for every estimator: its sample reach and
//! every world-radius term (falloff, R², normalisation) must follow the cap.

use crate::common::*;
use glam::Vec3;
use obscura::settings::Resolution;
use obscura::technique::{Estimator, Needs, Schedule, TABLE};
use obscura::{AoSettings, Renderer};

const WALL_DEPTH: f32 = 4.0;
const CAP_PX: f32 = 8.0;
const RADIUS: f32 = 1.0;

/// A wall facing the camera at depth 4 with a fin standing out of it and a shelf below: both
/// occlude the wall near them.
fn wall_fin_shelf() -> obscura::scene::Scene {
    let z = -WALL_DEPTH;
    quads(
        "wall, fin and shelf",
        &[
            [
                Vec3::new(-20.0, -20.0, z),
                Vec3::new(20.0, -20.0, z),
                Vec3::new(20.0, 20.0, z),
                Vec3::new(-20.0, 20.0, z),
            ],
            // The fin at x = 0.3, facing the camera's side (−x).
            [
                Vec3::new(0.3, -3.0, z + 0.8),
                Vec3::new(0.3, -3.0, z),
                Vec3::new(0.3, 3.0, z),
                Vec3::new(0.3, 3.0, z + 0.8),
            ],
            // The shelf at y = −0.6, facing up.
            [
                Vec3::new(-3.0, -0.6, z + 0.6),
                Vec3::new(3.0, -0.6, z + 0.6),
                Vec3::new(3.0, -0.6, z),
                Vec3::new(-3.0, -0.6, z),
            ],
        ],
    )
}

/// Raw AO (no blur) of `settings` on the wall scene at 128×96 + 16 px, whether each of its
/// pixels shows the wall (at half resolution: all four pixels it covers), and the pixels per
/// world unit of the output image at the wall's depth.
fn raw_ao(gpu: &obscura::Gpu, settings: &AoSettings) -> (Vec<f32>, Vec<bool>, f32) {
    let scene = wall_fin_shelf();
    let camera = camera(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), 60.0);
    let (w, h) = (128, 96);
    let mut r = Renderer::new(gpu, &scene, settings, w, h, 16).unwrap();
    r.render(&camera, None).unwrap();
    let screen = r.view().unwrap().screen();
    let depth = r.read_gbuffer().unwrap().visible_depth(screen.guard_band);
    let (w, half_w) = (w as usize, w as usize / 2);
    let on_wall = |x: usize, y: usize| (depth[y * w + x] - WALL_DEPTH).abs() < 1e-3;
    let wall = match settings.resolution {
        Resolution::Full => (0..depth.len()).map(|i| on_wall(i % w, i / w)).collect(),
        Resolution::Half => (0..depth.len() / 4)
            .map(|i| {
                let (x, y) = (2 * (i % half_w), 2 * (i / half_w));
                on_wall(x, y) && on_wall(x + 1, y) && on_wall(x, y + 1) && on_wall(x + 1, y + 1)
            })
            .collect(),
    };
    let per_unit = screen.pixels_per_unit(WALL_DEPTH).y;
    (r.read_raw_ao().unwrap(), wall, per_unit)
}

/// A capped R against R' on the wall's pixels for `s` (its radius R, its cap CAP_PX; GTAO's
/// samples reach `reach` R): the images must agree, and differ from the uncapped R.
fn assert_cap_is_the_smaller_radius(gpu: &obscura::Gpu, s: &AoSettings, reach: f32, label: &str) {
    let mut s = *s;
    s.set_radius(RADIUS);
    s.max_radius_px = CAP_PX;
    let (capped, wall, per_unit) = raw_ao(gpu, &s);
    assert!(
        RADIUS * reach * per_unit > 2.0 * CAP_PX,
        "the cap must bind on the wall"
    );
    s.set_radius(CAP_PX / per_unit / reach);
    s.max_radius_px = 0.0;
    let smaller = raw_ao(gpu, &s).0;
    s.set_radius(RADIUS);
    let uncapped = raw_ao(gpu, &s).0;

    let wall: Vec<usize> = (0..wall.len()).filter(|&i| wall[i]).collect();
    assert!(
        wall.len() > capped.len() / 2,
        "{label}: the wall fills the view"
    );
    let mean = |a: &[f32], b: &[f32]| {
        wall.iter()
            .map(|&i| (a[i] - b[i]).abs() as f64)
            .sum::<f64>()
            / wall.len() as f64
    };
    // Sample positions computed from R one way or the other may snap to a neighbouring pixel
    // where they lie on a pixel edge: a few pixels may differ, the mean hardly.
    let differing = wall
        .iter()
        .filter(|&&i| (capped[i] - smaller[i]).abs() > 2e-3)
        .count();
    let (same, cap_effect) = (mean(&capped, &smaller), mean(&capped, &uncapped));
    let largest_effect = wall
        .iter()
        .map(|&i| (capped[i] - uncapped[i]).abs())
        .fold(0.0f32, f32::max);
    println!(
        "{label}: mean |capped − R'| {same:.2e} ({differing} of {} px > 2e-3), mean |capped − R| {cap_effect:.3}, max {largest_effect:.3}",
        wall.len()
    );
    assert!(
        same <= 5e-4 && differing * 50 <= wall.len(),
        "{label}: capped R and R' differ: mean {same}, {differing} pixels"
    );
    assert!(
        cap_effect >= 1e-3 && largest_effect >= 0.03,
        "{label}: the cap must change the image (mean change {cap_effect}, max {largest_effect})"
    );
    assert!(
        wall.iter().any(|&i| uncapped[i] < 0.95) && wall.iter().any(|&i| capped[i] < 0.99),
        "{label}: the fin and shelf must occlude the wall, capped or not"
    );
}

#[test]
fn every_estimator_with_its_radius_capped_equals_the_smaller_radius_on_a_facing_wall() {
    let gpu = gpu();
    // One single-pass row per estimator over the depth buffer (or its pyramid): a source that
    // needs nothing beyond depth and normals and reads no estimator's own rays.
    let mut seen = Vec::new();
    for row in TABLE.iter().filter(|r| {
        r.schedule == Schedule::Single
            && r.source.needs() == Needs::default()
            && r.source.caps().only_for.is_none()
    }) {
        if seen.contains(&row.estimator) {
            continue;
        }
        seen.push(row.estimator);
        // GTAO's samples reach 1.457 R (XeGTAO's multiplier): the cap binds the reach.
        let reach = match row.estimator {
            Estimator::Gtao => obscura::estimators::gtao::reach(RADIUS) / RADIUS,
            _ => 1.0,
        };
        let s = technique_settings(row.technique, false);
        assert_cap_is_the_smaller_radius(&gpu, &s, reach, row.name);
    }
    // Every estimator but hemisphere, whose rays are world-space and never capped
    // (hemisphere.wgsl): its rows run over its own rays, not the depth buffer.
    let unseen: Vec<_> = Estimator::all()
        .into_iter()
        .filter(|e| !seen.contains(e))
        .map(|e| e.name())
        .collect();
    assert_eq!(unseen, ["hemisphere"], "seen: {seen:?}");
}

#[test]
fn at_half_resolution_the_cap_counts_output_pixels() {
    // The same cap in output pixels gives the same world radius at half resolution, where a
    // pixel is twice as wide: R' = cap / (output pixels per unit).
    let mut s = technique_settings(obscura::Technique::Vao, false);
    s.resolution = Resolution::Half;
    assert_cap_is_the_smaller_radius(&gpu(), &s, 1.0, "vao at half resolution");
}
