//! `layers`: a pillar wrapped in ten concentric shells before a background wall (paper 001,
//! Fig. 8).
//!
//! The shells are open, double-sided cylinders 3 cm apart, each shorter than the one inside it,
//! cut open towards the cameras with openings that widen outwards (a stepped cut-away): every
//! shell's edge shows in front of the ones inside, and behind the openings many depth layers
//! overlap in one pixel, the stress case for stochastic depth maps with few samples.

use std::f32::consts::TAU;

use glam::Vec3;

use super::builder::{Builder, Cylinder};

/// Shells of the built-in scene.
pub(super) const SHELLS: usize = 10;

pub(super) fn build() -> Builder {
    build_with(SHELLS)
}

/// The scene with the first `shells` shells (1 to 10), from the pillar outwards: seed 001 Fig. 8
/// adds 5 and 10 layers to a pillar.
pub(super) fn build_with(shells: usize) -> Builder {
    let mut b = Builder::new("layers");
    let floor = b.material("floor", [0.50, 0.47, 0.42], false);
    let wall = b.material("background wall", [0.75, 0.78, 0.82], false);
    let block = b.material("occluder block", [0.35, 0.55, 0.35], false);
    let pillar = b.material("pillar", [0.85, 0.82, 0.75], false);

    b.aabb(floor, Vec3::new(-4.0, -0.1, -4.0), Vec3::new(4.0, 0.0, 3.0));
    b.aabb(wall, Vec3::new(-3.0, 0.0, -2.2), Vec3::new(3.0, 3.0, -2.0));
    b.aabb(block, Vec3::new(1.0, 0.0, -1.5), Vec3::new(1.6, 1.4, -0.9));

    b.cylinder(pillar, &Cylinder::solid(Vec3::ZERO, 0.25, 2.2, 32));
    for k in 0..shells.min(SHELLS) {
        let t = k as f32 / (SHELLS - 1) as f32;
        // Hue ramp from warm (inner) to cool (outer), so layers are told apart in colour.
        let rgb = [0.9 - 0.6 * t, 0.45 + 0.2 * t, 0.2 + 0.7 * t];
        let mat = b.material(&format!("shell {}", k + 1), rgb, true);
        // Openings from 20° (inner) to 110° (outer), centred between +x and +z where the
        // cameras are.
        let opening = (20.0 + 10.0 * k as f32).to_radians();
        let gap_center = 60f32.to_radians();
        let shell = Cylinder {
            arc: (gap_center + 0.5 * opening, TAU - opening),
            ..Cylinder::shell(
                Vec3::ZERO,
                0.28 + 0.03 * k as f32,
                2.1 - 0.09 * k as f32,
                48,
                4,
            )
        };
        b.cylinder(mat, &shell);
    }

    b.camera(
        "closeup",
        Vec3::new(1.0, 1.5, 2.0),
        Vec3::new(0.0, 1.0, -1.0),
        45.0,
    );
    b.camera(
        "overview",
        Vec3::new(2.8, 2.4, 3.2),
        Vec3::new(0.0, 1.0, -0.8),
        55.0,
    );
    // Swing around the wrapped pillar: the shells' silhouettes move across the background
    // occluder (seed 001 Fig. 8).
    let look = Vec3::new(0.0, 1.0, -1.0);
    b.path(
        "orbit",
        &[
            (0.0, Vec3::new(-1.6, 1.5, 1.6), look, 45.0),
            (1.0, Vec3::new(-0.5, 1.5, 2.2), look, 45.0),
            (2.0, Vec3::new(0.7, 1.5, 2.1), look, 45.0),
            (3.0, Vec3::new(1.7, 1.5, 1.5), look, 45.0),
        ],
    );
    b
}
