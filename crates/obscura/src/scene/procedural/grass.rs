//! `grass`: thousands of thin blades standing on the ground around a rock (paper 000, Fig. 14:
//! the worst case, where nearly every sample is hidden behind some blade).
//!
//! Each blade is zero-thickness and double-sided: a tapering quad and a tip triangle, bent along
//! its normal. Positions, heights, widths, orientations, bends and shades come from a seeded
//! [`Pcg32`], so the scene is identical on every run.

use std::f32::consts::TAU;

use glam::{Vec2, Vec3};

use super::builder::Builder;
use super::rng::Pcg32;

const BLADES: usize = 4000;
/// Blades grow in the square [-PATCH, PATCH]² (x, z).
const PATCH: f32 = 2.0;
/// Eye of the close-up camera; a small clearing around it keeps blades off the lens.
const CLOSEUP_EYE: Vec3 = Vec3::new(0.35, 0.55, 1.15);
const CLEARING: f32 = 0.3;

pub(super) fn build() -> Builder {
    let mut b = Builder::new("grass");
    let soil = b.material("soil", [0.36, 0.27, 0.17], false);
    let rock = b.material("rock", [0.55, 0.55, 0.58], false);
    let greens = [
        b.material("grass dark", [0.12, 0.40, 0.08], true),
        b.material("grass mid", [0.25, 0.55, 0.12], true),
        b.material("grass light", [0.45, 0.65, 0.20], true),
    ];

    b.aabb(soil, Vec3::new(-5.0, -0.1, -5.0), Vec3::new(5.0, 0.0, 5.0));
    let rock_center = Vec3::new(0.3, 0.25, -0.6);
    let rock_half = Vec3::new(0.45, 0.25, 0.35);
    let rock_yaw = 0.4;
    b.cuboid(rock, rock_center, rock_half, rock_yaw);
    let rock_solid = super::Solid::Box {
        center: rock_center,
        half: rock_half + Vec3::new(0.02, 0.0, 0.02),
        yaw: rock_yaw,
    };

    // Seed: "grass" in ASCII.
    let mut rng = Pcg32::new(0x0067_7261_7373, 1);
    let mut placed = 0;
    while placed < BLADES {
        let root = Vec3::new(rng.range(-PATCH, PATCH), 0.0, rng.range(-PATCH, PATCH));
        // Draw every random number of the blade before deciding to skip it, so skipping one
        // does not shift the sequence of the others.
        let blade = Blade {
            root,
            height: rng.range(0.12, 0.45),
            width: rng.range(0.006, 0.012),
            yaw: rng.range(0.0, TAU),
            bend: rng.range(0.0, 0.35),
            shade: (rng.next_u32() % 3) as usize,
        };
        let near_eye =
            Vec2::new(root.x - CLOSEUP_EYE.x, root.z - CLOSEUP_EYE.z).length() < CLEARING;
        if near_eye || rock_solid.contains(root + Vec3::Y * 0.01) {
            continue;
        }
        blade.emit(&mut b, greens[blade.shade]);
        placed += 1;
    }

    b.camera("closeup", CLOSEUP_EYE, Vec3::new(0.3, 0.15, -0.6), 50.0);
    b.camera(
        "overview",
        Vec3::new(3.5, 2.2, 3.5),
        Vec3::new(0.0, 0.1, 0.0),
        55.0,
    );
    b.camera(
        "ground",
        Vec3::new(-2.6, 0.25, 2.6),
        Vec3::new(0.0, 0.2, 0.0),
        45.0,
    );
    // Walk into the patch at knee height: blades pass close to the camera, the worst case for
    // a single depth layer (seed 000 Fig. 14).
    b.path(
        "walk",
        &[
            (
                0.0,
                Vec3::new(-0.4, 0.6, 1.8),
                Vec3::new(0.2, 0.15, -0.4),
                50.0,
            ),
            (
                1.0,
                Vec3::new(0.0, 0.55, 1.4),
                Vec3::new(0.3, 0.15, -0.6),
                50.0,
            ),
            (
                2.0,
                Vec3::new(0.35, 0.55, 1.15),
                Vec3::new(0.3, 0.15, -0.6),
                50.0,
            ),
            (
                3.0,
                Vec3::new(0.7, 0.5, 0.9),
                Vec3::new(0.1, 0.15, -0.7),
                50.0,
            ),
        ],
    );
    b
}

struct Blade {
    root: Vec3,
    height: f32,
    width: f32,
    yaw: f32,
    /// Horizontal tip offset as a fraction of the height.
    bend: f32,
    shade: usize,
}

impl Blade {
    /// Three triangles: a quad from the root to 55 % height (tapering to 70 % width), then the
    /// tip. The bend grows quadratically with height, like a blade drooping under its weight.
    fn emit(&self, b: &mut Builder, mat: u32) {
        let across = Vec3::new(self.yaw.cos(), 0.0, self.yaw.sin());
        let lean = Vec3::new(-self.yaw.sin(), 0.0, self.yaw.cos()) * self.bend * self.height;
        let at = |t: f32| self.root + Vec3::Y * (t * self.height) + lean * (t * t);
        let (w0, w1) = (0.5 * self.width, 0.35 * self.width);
        let (base, mid, tip) = (at(0.0), at(0.55), at(1.0));
        b.quad(
            mat,
            [
                base - across * w0,
                base + across * w0,
                mid + across * w1,
                mid - across * w1,
            ],
        );
        let uv = [
            Vec2::new(0.0, 0.45),
            Vec2::new(1.0, 0.45),
            Vec2::new(0.5, 0.0),
        ];
        b.triangle(mat, [mid - across * w1, mid + across * w1, tip], uv);
    }
}
