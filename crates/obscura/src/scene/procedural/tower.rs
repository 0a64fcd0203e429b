//! `tower`: a spiral staircase around a central column inside a cylindrical tower (paper 002,
//! Fig. 1).
//!
//! Thin slab steps overlap each other in depth from almost every view, and the tower wall faces
//! inward, so the camera is always enclosed: rays hit something in every direction.

use std::f32::consts::TAU;

use glam::Vec3;

use super::builder::{Builder, Cylinder, Facing};

const STEPS: usize = 32;
const STEPS_PER_TURN: usize = 16;
const RISE: f32 = 0.17;
const COLUMN_RADIUS: f32 = 0.3;
const STEP_OUTER_RADIUS: f32 = 2.9;
const TOWER_RADIUS: f32 = 3.0;
const TOWER_HEIGHT: f32 = 8.0;

pub(super) fn build() -> Builder {
    let mut b = Builder::new("tower");
    let floor = b.material("floor", [0.40, 0.38, 0.36], false);
    let wall = b.material("tower wall", [0.82, 0.72, 0.55], false);
    let column = b.material("column", [0.60, 0.62, 0.66], false);
    let steps = b.material("steps", [0.55, 0.35, 0.20], false);

    b.aabb(floor, Vec3::new(-3.6, -0.1, -3.6), Vec3::new(3.6, 0.0, 3.6));
    let tower = Cylinder {
        facing: Facing::Inward,
        ..Cylinder::shell(Vec3::ZERO, TOWER_RADIUS, TOWER_HEIGHT, 64, 8)
    };
    b.cylinder(wall, &tower);
    b.cylinder(column, &Cylinder::solid(Vec3::ZERO, COLUMN_RADIUS, 5.7, 32));

    // Each step is an 8 cm slab from the column to 10 cm short of the wall, as wide at its outer
    // end as one step's angle; it rotates by that angle per step.
    let step_angle = TAU / STEPS_PER_TURN as f32;
    let radial_half = 0.5 * (STEP_OUTER_RADIUS - COLUMN_RADIUS);
    let mid_radius = COLUMN_RADIUS + radial_half;
    let tangential_half = STEP_OUTER_RADIUS * (0.5 * step_angle).tan() + 0.005;
    for i in 0..STEPS {
        let phi = i as f32 * step_angle;
        let top = (i + 1) as f32 * RISE;
        let center = Vec3::new(mid_radius * phi.cos(), top - 0.04, mid_radius * phi.sin());
        // yaw = -phi turns the box's local +X onto the radial direction (cos φ, 0, sin φ).
        b.cuboid(
            steps,
            center,
            Vec3::new(radial_half, 0.04, tangential_half),
            -phi,
        );
    }

    b.camera(
        "closeup",
        Vec3::new(2.2, 1.3, -1.3),
        Vec3::new(0.2, 0.9, 1.6),
        55.0,
    );
    // Straight down, beside the column top: `Camera::new` picks up = -Z here.
    b.camera(
        "overview",
        Vec3::new(1.6, 7.8, 0.0),
        Vec3::new(1.6, 0.0, 0.0),
        60.0,
    );
    // Up the spiral from under step 15 (its underside is 2.5 m above the eye).
    b.camera(
        "lookup",
        Vec3::new(1.85, 1.0, -0.77),
        Vec3::new(-0.5, 5.5, 0.5),
        60.0,
    );
    // Climb the spiral: the eye walks 1.5 turns up the steps, 1.4 m above them, looking ahead
    // along the stairs (seed 002 Fig. 1).
    let keys: Vec<(f32, Vec3, Vec3, f32)> = (0..7)
        .map(|k| {
            let phi = 0.6 + k as f32 * 0.25 * TAU;
            let height = |phi: f32| (phi / (TAU / STEPS_PER_TURN as f32) + 1.0) * RISE + 1.4;
            let at = |phi: f32, radius: f32, lift: f32| {
                Vec3::new(radius * phi.cos(), height(phi) + lift, radius * phi.sin())
            };
            (
                k as f32 * 0.5,
                at(phi, 1.9, 0.0),
                at(phi + 1.2, 1.4, -0.3),
                60.0,
            )
        })
        .collect();
    b.path("climb", &keys);
    b
}
