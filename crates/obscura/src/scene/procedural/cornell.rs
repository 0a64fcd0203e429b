//! `cornell`: a Cornell box with a tall and a short block (sanity scene).
//!
//! 2 m cube interior (x, z in [-1, 1], y in [0, 2]), open towards +z, walls as 4 cm closed slabs,
//! the classic colours (white, red left, green right) and blocks turned by ±17°.

use glam::Vec3;

use super::builder::Builder;

pub(super) fn build() -> Builder {
    let mut b = Builder::new("cornell");
    let white = b.material("white", [0.725, 0.71, 0.68], false);
    let red = b.material("red", [0.63, 0.065, 0.05], false);
    let green = b.material("green", [0.14, 0.45, 0.091], false);
    let light = b.material("light", [1.0, 0.93, 0.75], false);
    let tall = b.material("tall block", [0.80, 0.78, 0.72], false);
    let short = b.material("short block", [0.70, 0.72, 0.80], false);

    let t = 0.04;
    b.aabb(
        white,
        Vec3::new(-1.0 - t, -t, -1.0 - t),
        Vec3::new(1.0 + t, 0.0, 1.0),
    );
    b.aabb(
        white,
        Vec3::new(-1.0 - t, 2.0, -1.0 - t),
        Vec3::new(1.0 + t, 2.0 + t, 1.0),
    );
    b.aabb(
        white,
        Vec3::new(-1.0 - t, 0.0, -1.0 - t),
        Vec3::new(1.0 + t, 2.0, -1.0),
    );
    b.aabb(
        red,
        Vec3::new(-1.0 - t, 0.0, -1.0),
        Vec3::new(-1.0, 2.0, 1.0),
    );
    b.aabb(
        green,
        Vec3::new(1.0, 0.0, -1.0),
        Vec3::new(1.0 + t, 2.0, 1.0),
    );
    b.aabb(
        light,
        Vec3::new(-0.25, 1.99, -0.25),
        Vec3::new(0.25, 2.0, 0.25),
    );

    let yaw = 17f32.to_radians();
    b.cuboid(
        tall,
        Vec3::new(-0.33, 0.6, -0.3),
        Vec3::new(0.3, 0.6, 0.3),
        yaw,
    );
    b.cuboid(
        short,
        Vec3::new(0.33, 0.3, 0.3),
        Vec3::new(0.3, 0.3, 0.3),
        -yaw,
    );

    b.camera(
        "closeup",
        Vec3::new(0.75, 0.5, 1.6),
        Vec3::new(-0.1, 0.55, -0.5),
        45.0,
    );
    b.camera(
        "overview",
        Vec3::new(0.0, 1.0, 3.9),
        Vec3::new(0.0, 1.0, 0.0),
        40.0,
    );
    // Pan across the open front: the blocks' edges move over the walls behind them.
    let look = Vec3::new(0.0, 0.55, -0.5);
    b.path(
        "pan",
        &[
            (0.0, Vec3::new(-0.75, 0.5, 1.6), look, 45.0),
            (1.0, Vec3::new(0.0, 0.55, 1.7), look, 45.0),
            (2.0, Vec3::new(0.75, 0.5, 1.6), look, 45.0),
        ],
    );
    b
}
