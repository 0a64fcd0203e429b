//! `colonnade`: two rows of pillars before a wall with a framed, mullioned window, before a back
//! wall (paper 000, Fig. 10). A view ray through the window passes up to three occluders (pillar,
//! window frame, back wall), so a sample can be hidden behind more than one layer.

use glam::Vec3;

use super::builder::{Builder, Cylinder};

/// Window opening in the middle wall: x half-width, bottom and top heights.
const WIN_HALF: f32 = 1.2;
const WIN_BOTTOM: f32 = 0.8;
const WIN_TOP: f32 = 2.6;
/// Middle (window) wall z range.
const WALL_Z: (f32, f32) = (-4.2, -4.0);
const HEIGHT: f32 = 4.0;

pub(super) fn build() -> Builder {
    let mut b = Builder::new("colonnade");
    let floor = b.material("floor", [0.45, 0.45, 0.50], false);
    let back = b.material("back wall", [0.85, 0.75, 0.55], false);
    let wall = b.material("window wall", [0.70, 0.72, 0.78], false);
    let frame = b.material("window frame", [0.35, 0.22, 0.12], false);
    let pillar = b.material("pillars", [0.92, 0.90, 0.85], false);
    let stone = b.material("plinths", [0.60, 0.58, 0.55], false);

    b.aabb(floor, Vec3::new(-6.0, -0.1, -8.0), Vec3::new(6.0, 0.0, 4.0));
    b.aabb(
        back,
        Vec3::new(-6.0, 0.0, -7.2),
        Vec3::new(6.0, HEIGHT, -7.0),
    );
    window_wall(&mut b, wall, frame);

    // Front row on the window's axis, back row staggered between.
    let rows = [
        (-1.5, [-4.5, -2.25, 0.0, 2.25, 4.5].as_slice()),
        (-2.8, &[-3.375, -1.125, 1.125, 3.375]),
    ];
    for (z, xs) in rows {
        for &x in xs {
            let base = Vec3::new(x, 0.0, z);
            b.aabb(
                stone,
                base + Vec3::new(-0.28, 0.0, -0.28),
                base + Vec3::new(0.28, 0.16, 0.28),
            );
            b.cylinder(
                pillar,
                &Cylinder::solid(base + Vec3::Y * 0.16, 0.18, 3.3, 24),
            );
            let top = Vec3::Y * 3.46;
            b.aabb(
                stone,
                base + top + Vec3::new(-0.26, 0.0, -0.26),
                base + top + Vec3::new(0.26, 0.14, 0.26),
            );
        }
    }

    b.camera(
        "closeup",
        Vec3::new(0.5, 1.6, 0.6),
        Vec3::new(0.0, 1.6, -4.1),
        50.0,
    );
    b.camera(
        "overview",
        Vec3::new(5.0, 3.5, 4.0),
        Vec3::new(0.0, 1.5, -3.0),
        60.0,
    );
    b.camera(
        "through",
        Vec3::new(-0.9, 1.2, 2.5),
        Vec3::new(0.3, 1.7, -7.0),
        45.0,
    );
    // Truck along the front row of pillars: each pillar passes before the window frame and the
    // wall, up to three occluders deep (seed 000 Fig. 10).
    b.path(
        "truck",
        &[
            (
                0.0,
                Vec3::new(-2.4, 1.6, 0.6),
                Vec3::new(-2.4, 1.6, -4.1),
                50.0,
            ),
            (
                1.0,
                Vec3::new(-0.8, 1.6, 0.6),
                Vec3::new(-0.8, 1.6, -4.1),
                50.0,
            ),
            (
                2.0,
                Vec3::new(0.8, 1.6, 0.6),
                Vec3::new(0.8, 1.6, -4.1),
                50.0,
            ),
            (
                3.0,
                Vec3::new(2.4, 1.6, 0.6),
                Vec3::new(2.4, 1.6, -4.1),
                50.0,
            ),
        ],
    );
    b
}

/// The middle wall as four boxes around the opening, a frame lining it and a mullion cross.
fn window_wall(b: &mut Builder, wall: u32, frame: u32) {
    let (z0, z1) = WALL_Z;
    let box_ = |b: &mut Builder, m, x: (f32, f32), y: (f32, f32), z: (f32, f32)| {
        b.aabb(m, Vec3::new(x.0, y.0, z.0), Vec3::new(x.1, y.1, z.1));
    };
    box_(b, wall, (-6.0, -WIN_HALF), (0.0, HEIGHT), (z0, z1));
    box_(b, wall, (WIN_HALF, 6.0), (0.0, HEIGHT), (z0, z1));
    box_(b, wall, (-WIN_HALF, WIN_HALF), (0.0, WIN_BOTTOM), (z0, z1));
    box_(b, wall, (-WIN_HALF, WIN_HALF), (WIN_TOP, HEIGHT), (z0, z1));

    // The frame sticks out 10 cm on both sides of the wall.
    let fz = (z0 - 0.1, z1 + 0.1);
    let t = 0.08;
    let (l, r, bot, top) = (-WIN_HALF, WIN_HALF, WIN_BOTTOM, WIN_TOP);
    box_(b, frame, (l, l + t), (bot + t, top - t), fz);
    box_(b, frame, (r - t, r), (bot + t, top - t), fz);
    box_(b, frame, (l, r), (bot, bot + t), fz);
    box_(b, frame, (l, r), (top - t, top), fz);
    // Mullion cross: 6 cm bars, 8 cm deep, centred in the wall: thin occluders in the opening.
    let mz = (0.5 * (z0 + z1) - 0.04, 0.5 * (z0 + z1) + 0.04);
    let mid = 0.5 * (bot + top);
    box_(b, frame, (-0.03, 0.03), (bot + t, top - t), mz);
    box_(b, frame, (l + t, -0.03), (mid - 0.03, mid + 0.03), mz);
    box_(b, frame, (0.03, r - t), (mid - 0.03, mid + 0.03), mz);
}
