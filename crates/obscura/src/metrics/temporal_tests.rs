//! Temporal metrics on analytic fixtures: a camera trucking over a plane facing it, pops and
//! disocclusions painted into known blocks.

use super::*;
use crate::scene::Camera;
use glam::{Vec2, Vec3};

const W: usize = 64;
const H: usize = 48;
/// The plane z = 0 seen from z = 5: every pixel's linear depth is 5.
const PLANE_DEPTH: f32 = 5.0;

fn view(x: f32, guard_band: u32) -> FrameView {
    let camera = Camera::new(Vec3::new(x, 0.0, 5.0), Vec3::new(x, 0.0, 0.0), 60.0).unwrap();
    FrameView::new(camera, W as u32, H as u32, guard_band, 0.1)
}

/// World x of every visible pixel's point on the plane.
fn world_x(v: &FrameView) -> Vec<f32> {
    let to_world = v.view_matrix().inverse();
    let g = v.guard_band as f32;
    (0..W * H)
        .map(|i| {
            let px = Vec2::new((i % W) as f32 + 0.5 + g, (i / W) as f32 + 0.5 + g);
            to_world
                .transform_point3(v.screen().pixel_to_view(px, PLANE_DEPTH))
                .x
        })
        .collect()
}

fn pattern(x: f32) -> f32 {
    0.5 + 0.4 * (3.0 * x).sin()
}

#[test]
fn a_pattern_fixed_on_the_surface_does_not_flicker_when_the_camera_moves() {
    let depth = vec![PLANE_DEPTH; W * H];
    let (v0, v1) = (view(0.0, 4), view(0.2, 4));
    let frames = [
        PathFrame {
            view: v0,
            depth: &depth,
        },
        PathFrame {
            view: v1,
            depth: &depth,
        },
    ];
    let ao: Vec<Vec<f32>> = [v0, v1]
        .iter()
        .map(|v| world_x(v).into_iter().map(pattern).collect())
        .collect();
    let still = vec![vec![0.7; W * H]; 2];
    let m = path_metrics(&frames, &ao, &still).unwrap();
    // Only the bilinear interpolation error of a smooth pattern: at most |f''|·h²/8 = 0.0065
    // with f'' ≤ 3.6 and h = 0.12 m per pixel at 5 m (measured: 0.0037 on average).
    println!("world-fixed pattern: {m:?}");
    assert!(m.temporal_error < 6e-3, "{m:?}");
    assert_eq!(m.popping, 0.0);
    // The strip that entered the view on the right is unmatched: 0.2 m of the 2·5·tan 30° · 64/48
    // m wide visible image.
    let visible_width = 2.0 * 5.0 * (30f32.to_radians()).tan() * W as f32 / H as f32;
    let expected = 1.0 - 0.2 / visible_width;
    assert!(
        (m.pairs[0].matched - f64::from(expected)).abs() < 1.5 / W as f64,
        "{} vs {expected}",
        m.pairs[0].matched
    );

    // The same pattern fixed on the screen instead slides over the surface: its change is
    // pattern(x) - pattern(x - 0.2) at every matched pixel.
    let screen_fixed = vec![ao[0].clone(), ao[0].clone()];
    let m = path_metrics(&frames, &screen_fixed, &still).unwrap();
    let reprojection = Reprojection::new(&frames[0], &frames[1]).unwrap();
    let x1 = world_x(&v1);
    let (mut sum, mut n) = (0.0f64, 0);
    for (i, &x) in x1.iter().enumerate() {
        if reprojection.sample(&ao[0], i).is_some() {
            // Frame 1 shows pattern(x - 0.2) at the surface point x, frame 0 showed pattern(x).
            sum += f64::from((pattern(x - 0.2) - pattern(x)).abs());
            n += 1;
        }
    }
    let expected = sum / n as f64;
    assert!(
        (m.temporal_error - expected).abs() < 0.03 * expected,
        "{} vs {expected}",
        m.temporal_error
    );
    assert!(m.temporal_error > 0.1);
}

#[test]
fn popping_counts_changes_the_reference_does_not_make() {
    let depth = vec![PLANE_DEPTH; W * H];
    let v = view(0.0, 0);
    let frames = [
        PathFrame {
            view: v,
            depth: &depth,
        },
        PathFrame {
            view: v,
            depth: &depth,
        },
    ];
    // Left quarter: the technique brightens by 0.2, the reference stays: pops. Second quarter:
    // both brighten by 0.2: no pop, no temporal error. Third quarter: the technique changes by
    // 0.05 only: no pop, error 0.05.
    let quarter = |i: usize| (i % W) / (W / 4);
    let a0 = vec![0.5; W * H];
    let a1: Vec<f32> = (0..W * H)
        .map(|i| match quarter(i) {
            0 | 1 => 0.7,
            2 => 0.55,
            _ => 0.5,
        })
        .collect();
    let r0 = vec![0.5; W * H];
    let r1: Vec<f32> = (0..W * H)
        .map(|i| if quarter(i) == 1 { 0.7 } else { 0.5 })
        .collect();
    let m = path_metrics(&frames, &[a0, a1], &[r0, r1]).unwrap();
    assert_eq!(m.pairs[0].matched, 1.0);
    assert!((m.popping - 0.25).abs() < 1e-12, "{m:?}");
    assert!(
        (m.temporal_error - (0.25 * 0.2 + 0.25 * 0.05)).abs() < 1e-6,
        "{m:?}"
    );
}

#[test]
fn disoccluded_and_empty_pixels_are_not_matched() {
    let v = view(0.0, 0);
    // Frame 0 had an occluder 2 m from the eye over the top half; frame 1 sees the plane there.
    // The left eighth of frame 1 shows nothing (background).
    let d0: Vec<f32> = (0..W * H)
        .map(|i| if i / W < H / 2 { 2.0 } else { PLANE_DEPTH })
        .collect();
    let d1: Vec<f32> = (0..W * H)
        .map(|i| if i % W < W / 8 { 0.0 } else { PLANE_DEPTH })
        .collect();
    let frames = [
        PathFrame {
            view: v,
            depth: &d0,
        },
        PathFrame {
            view: v,
            depth: &d1,
        },
    ];
    // Everything unmatched differs wildly; matched pixels agree.
    let a0: Vec<f32> = (0..W * H)
        .map(|i| if i / W < H / 2 { 0.0 } else { 0.6 })
        .collect();
    let a1 = vec![0.6; W * H];
    let r = vec![vec![0.6; W * H]; 2];
    let m = path_metrics(&frames, &[a0, a1], &r).unwrap();
    let expected = 0.5 * (1.0 - 1.0 / 8.0);
    assert!((m.pairs[0].matched - expected).abs() < 1e-12, "{m:?}");
    assert_eq!(m.temporal_error, 0.0);
    assert_eq!(m.popping, 0.0);
}

#[test]
fn pairs_pool_by_matched_pixels() {
    let depth = vec![PLANE_DEPTH; W * H];
    let v = view(0.0, 0);
    let frames = [PathFrame {
        view: v,
        depth: &depth,
    }; 3];
    let ao = vec![vec![0.5; W * H], vec![0.58; W * H], vec![0.58; W * H]];
    let r = vec![vec![0.5; W * H]; 3];
    let m = path_metrics(&frames, &ao, &r).unwrap();
    assert_eq!(m.pairs.len(), 2);
    assert!((m.pairs[0].temporal_error - 0.08).abs() < 1e-6);
    assert!(m.pairs[1].temporal_error < 1e-6);
    assert!((m.temporal_error - 0.04).abs() < 1e-6);
    assert_eq!((m.pairs[0].popping, m.pairs[1].popping), (0.0, 0.0));
}

#[test]
fn bad_inputs_are_errors() {
    let depth = vec![PLANE_DEPTH; W * H];
    let v = view(0.0, 0);
    let frame = PathFrame {
        view: v,
        depth: &depth,
    };
    let short = vec![PLANE_DEPTH; W * H - 1];
    let bad = PathFrame {
        view: v,
        depth: &short,
    };
    assert!(matches!(
        Reprojection::new(&frame, &bad),
        Err(MetricsError::DataLength { .. })
    ));
    let other = PathFrame {
        view: FrameView::new(v.camera, 32, 24, 0, 0.1),
        depth: &depth[..32 * 24],
    };
    assert!(matches!(
        Reprojection::new(&other, &frame),
        Err(MetricsError::SizeMismatch { .. })
    ));
    let ok = vec![0.5; W * H];
    let mut nan = ok.clone();
    nan[7] = f32::NAN;
    let reprojection = Reprojection::new(&frame, &frame).unwrap();
    assert!(matches!(
        pair_metrics(&reprojection, (&ok, &nan), (&ok, &ok)),
        Err(MetricsError::NonFinite {
            image: "technique",
            ..
        })
    ));
    assert!(matches!(
        path_metrics(
            &[frame, frame],
            std::slice::from_ref(&ok),
            &[ok.clone(), ok.clone()]
        ),
        Err(MetricsError::InvalidParameter { .. })
    ));
}
