//! Built-in procedural scenes, the embedded default.
//!
//! Each is deterministic, in metres with +Y up, small enough to rasterise on a CPU Vulkan driver,
//! and built to provoke one artifact the AO papers fix. Each has at least two named cameras: first
//! a close-up where a thin foreground object stands in front of a farther surface (where a
//! screen-space AO draws a bright or dark halo around the silhouette), then a wider overview.

mod builder;
mod colonnade;
mod cornell;
mod grass;
mod grazing;
mod layers;
pub(super) mod rng;
mod stairs;
#[cfg(test)]
mod tests;
mod tower;

use super::{Scene, SceneError};
use builder::Solid;

/// Names of the built-in scenes, in presentation order.
pub fn builtin_names() -> &'static [&'static str] {
    &[
        "stairs",
        "colonnade",
        "layers",
        "grass",
        "tower",
        "cornell",
        "grazing",
    ]
}

/// The built-in `layers` scene with only its `shells` innermost shells (1 to 10; the built-in has
/// 10): seed 001 Fig. 8 shows AO behind 5 and 10 added layers. Cameras and everything else as
/// `layers`.
pub fn layers_with_shells(shells: usize) -> Result<Scene, SceneError> {
    if !(1..=layers::SHELLS).contains(&shells) {
        return Err(SceneError::UnknownScene {
            spec: format!(
                "layers with {shells} shells (1 to {} exist)",
                layers::SHELLS
            ),
        });
    }
    let scene = layers::build_with(shells).finish().0;
    scene.validate()?;
    Ok(scene)
}

/// Builds the built-in scene `name` (validated).
pub fn builtin(name: &str) -> Result<Scene, SceneError> {
    let scene = build(name)
        .ok_or_else(|| SceneError::UnknownScene {
            spec: name.to_string(),
        })?
        .0;
    scene.validate()?;
    Ok(scene)
}

/// The scene and the closed solids it is made of (tests check cameras against them).
fn build(name: &str) -> Option<(Scene, Vec<Solid>)> {
    let builder = match name {
        "stairs" => stairs::build(),
        "colonnade" => colonnade::build(),
        "layers" => layers::build(),
        "grass" => grass::build(),
        "tower" => tower::build(),
        "cornell" => cornell::build(),
        "grazing" => grazing::build(),
        _ => return None,
    };
    Some(builder.finish())
}
