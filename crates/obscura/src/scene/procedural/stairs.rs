//! `stairs`: a figure of thin cloth layers in front of a staircase (paper 000, Fig. 1).
//!
//! Three concentric, double-sided, wavy shells a few centimetres apart, opened towards the
//! viewer, stand before twelve steps. A single depth layer sees only the outer cloth, so the
//! staircase behind it gets a halo, and the inner layers are lost.

use std::f32::consts::TAU;

use glam::Vec3;

use super::builder::{Builder, Cylinder, Solid};

const STEPS: usize = 12;
const RISE: f32 = 0.18;
const RUN: f32 = 0.3;
const HALF_WIDTH: f32 = 1.5;
/// z of the first riser; the stairs climb towards -z.
const FRONT_Z: f32 = -1.0;

pub(super) fn build() -> Builder {
    let mut b = Builder::new("stairs");
    let floor = b.material("floor", [0.55, 0.50, 0.45], false);
    let stone = b.material("stairs", [0.78, 0.74, 0.66], false);
    let wall = b.material("wall", [0.62, 0.68, 0.74], false);
    let cloth = [
        b.material("cloth inner", [0.20, 0.35, 0.70], true),
        b.material("cloth middle", [0.85, 0.65, 0.20], true),
        b.material("cloth outer", [0.70, 0.15, 0.15], true),
    ];
    let skin = b.material("head", [0.90, 0.75, 0.60], false);

    b.aabb(floor, Vec3::new(-4.0, -0.1, -5.0), Vec3::new(4.0, 0.0, 3.0));
    staircase(&mut b, stone);
    // A wall 5 cm behind the top step, so every view of the figure has a surface behind it.
    let back = FRONT_Z - STEPS as f32 * RUN - 0.05;
    b.aabb(
        wall,
        Vec3::new(-4.0, 0.0, back - 0.2),
        Vec3::new(4.0, 3.5, back),
    );

    // The figure: shells 4 cm apart with cloth folds of ±8 mm; the outer two are open towards +z
    // (angle τ/4) so the inner layers show through.
    let center = Vec3::new(0.15, 0.0, -0.45);
    let shells = [
        (0.22, 1.45, 1.0, 7.0),
        (0.26, 1.35, 0.89, 9.0),
        (0.30, 1.2, 0.83, 11.0),
    ];
    for (&mat, &(radius, height, covered, folds)) in cloth.iter().zip(&shells) {
        let sweep = TAU * covered;
        let gap_center = TAU / 4.0;
        b.cylinder(
            mat,
            &Cylinder {
                arc: (gap_center + 0.5 * (TAU - sweep), sweep),
                wobble: (0.008, folds),
                ..Cylinder::shell(center, radius, height, 48, 6)
            },
        );
    }
    b.cylinder(
        skin,
        &Cylinder::solid(center + Vec3::Y * 1.45, 0.11, 0.25, 24),
    );

    b.camera(
        "closeup",
        Vec3::new(0.85, 1.35, 1.2),
        Vec3::new(0.05, 0.85, -1.2),
        50.0,
    );
    b.camera(
        "overview",
        Vec3::new(3.2, 2.6, 3.4),
        Vec3::new(0.0, 0.8, -1.3),
        55.0,
    );
    b.camera(
        "side",
        Vec3::new(-3.4, 1.4, 0.8),
        Vec3::new(0.0, 0.9, -1.0),
        50.0,
    );
    // Dolly sideways past the figure: its silhouette sweeps across the steps behind it, where a
    // single depth layer makes halos appear and vanish (seed 001 §1).
    let look = Vec3::new(0.1, 0.85, -1.2);
    b.path(
        "dolly",
        &[
            (0.0, Vec3::new(-1.3, 1.35, 1.3), look, 50.0),
            (1.0, Vec3::new(-0.4, 1.3, 1.2), look, 50.0),
            (2.0, Vec3::new(0.5, 1.3, 1.2), look, 50.0),
            (3.0, Vec3::new(1.4, 1.35, 1.3), look, 50.0),
        ],
    );
    b
}

/// A straight staircase as one closed solid: risers, treads, back, bottom and stepped sides (no
/// faces inside, unlike stacked boxes, so ray-traced sample columns see two surfaces, not 2N).
fn staircase(b: &mut Builder, mat: u32) {
    let w = HALF_WIDTH;
    let h = STEPS as f32 * RISE;
    let back = FRONT_Z - STEPS as f32 * RUN;
    for i in 0..STEPS {
        let front = FRONT_Z - i as f32 * RUN;
        let top = (i + 1) as f32 * RISE;
        let mid_z = front - 0.5 * RUN;
        let riser = Vec3::new(0.0, top - 0.5 * RISE, front);
        b.rect(mat, riser, Vec3::X * w, Vec3::Y * 0.5 * RISE);
        let tread = Vec3::new(0.0, top, mid_z);
        b.rect(mat, tread, Vec3::Z * 0.5 * RUN, Vec3::X * w);
        let (u, v) = (Vec3::Y * 0.5 * top, Vec3::Z * 0.5 * RUN);
        b.rect(mat, Vec3::new(w, 0.5 * top, mid_z), u, v);
        b.rect(mat, Vec3::new(-w, 0.5 * top, mid_z), v, u);
        b.add_solid(Solid::Box {
            center: Vec3::new(0.0, 0.5 * top, mid_z),
            half: Vec3::new(w, 0.5 * top, 0.5 * RUN),
            yaw: 0.0,
        });
    }
    let len = FRONT_Z - back;
    b.rect(
        mat,
        Vec3::new(0.0, 0.5 * h, back),
        Vec3::Y * 0.5 * h,
        Vec3::X * w,
    );
    let bottom = Vec3::new(0.0, 0.0, back + 0.5 * len);
    b.rect(mat, bottom, Vec3::X * w, Vec3::Z * 0.5 * len);
}
