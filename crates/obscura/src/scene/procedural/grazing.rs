//! `grazing`: thin panels standing edge-on to the camera (paper 001, Fig. 3).
//!
//! Two panels, 2 cm thick, stand on the floor along the close-up's line of sight. Their broad
//! faces are seen edge-on: a pixel or two wide in the depth buffer, so the floor beside them
//! barely sees them. Every single-view screen-space AO misses the occlusion there; a second view
//! from the side sees the faces (the multi-view schedule, seed 001 §3.4). A post in front of a
//! back wall gives the close-up its silhouettes against a farther surface.

use glam::Vec3;

use super::builder::Builder;

pub(super) fn build() -> Builder {
    let mut b = Builder::new("grazing");
    let floor = b.material("floor", [0.52, 0.50, 0.47], false);
    let wall = b.material("back wall", [0.70, 0.74, 0.80], false);
    let panel = b.material("panel", [0.80, 0.55, 0.30], false);
    let low = b.material("low panel", [0.35, 0.60, 0.45], false);
    let post = b.material("post", [0.45, 0.40, 0.65], false);

    b.aabb(floor, Vec3::new(-4.0, -0.1, -5.0), Vec3::new(4.0, 0.0, 4.0));
    b.aabb(wall, Vec3::new(-4.0, 0.0, -5.2), Vec3::new(4.0, 2.5, -5.0));
    // Along −z, in the close-up camera's vertical plane (x = 0) and 0.6 m to its left.
    b.aabb(
        panel,
        Vec3::new(-0.01, 0.0, -3.0),
        Vec3::new(0.01, 0.8, 0.5),
    );
    b.aabb(low, Vec3::new(-0.61, 0.0, -2.5), Vec3::new(-0.59, 0.4, 0.0));
    // A post to the right: its sides against the back wall are the close-up's silhouettes.
    b.aabb(post, Vec3::new(0.75, 0.0, 0.9), Vec3::new(0.9, 1.6, 1.05));

    b.camera(
        "closeup",
        Vec3::new(0.0, 1.0, 3.5),
        Vec3::new(0.0, 0.2, -1.5),
        45.0,
    );
    b.camera(
        "overview",
        Vec3::new(2.2, 2.0, 3.5),
        Vec3::new(0.0, 0.3, -1.0),
        50.0,
    );
    // Pan sideways: the panel seen edge-on turns towards the camera, the case seed 001 Fig. 3
    // builds its second view for.
    let look = Vec3::new(0.0, 0.2, -1.5);
    b.path(
        "pan",
        &[
            (0.0, Vec3::new(-1.5, 1.0, 3.3), look, 45.0),
            (1.0, Vec3::new(0.0, 1.0, 3.5), look, 45.0),
            (2.0, Vec3::new(1.5, 1.0, 3.3), look, 45.0),
        ],
    );
    b
}
