//! Rasterisation passes: the scene on the GPU and the G-buffer (with depth peeling). The stochastic
//! depth map, also rasterised, is a hidden-depth source: [`crate::sources::stochastic_depth`].

pub mod chunks;
pub mod gbuffer;
pub mod gbuffer_image;
pub mod gpu_scene;
pub(crate) mod occlusion_pyramid;
pub(crate) mod triangle_cull;

pub use gbuffer_image::GBufferImage;

/// What the raster passes' in-crate tests share: the adapter, and a second view of a scene.
#[cfg(test)]
pub(crate) mod test_support {
    use crate::gpu::{Gpu, GpuOptions};
    use crate::scene::{Camera, Scene};

    /// The test adapter (lavapipe in CI).
    pub fn gpu() -> Gpu {
        if std::env::var_os("XDG_RUNTIME_DIR").is_none_or(|v| v.is_empty()) {
            std::env::set_var("XDG_RUNTIME_DIR", std::env::temp_dir());
        }
        Gpu::new(&GpuOptions::default()).expect("a GPU adapter (install mesa-vulkan-drivers)")
    }

    /// `camera` turned and moved by a few hundredths of `scene`'s extent: another view of it.
    pub fn moved(scene: &Scene, camera: &Camera) -> Camera {
        let extent = scene.bounds().max - scene.bounds().min;
        let mut moved = *camera;
        moved.eye += extent * glam::Vec3::new(0.06, 0.03, -0.04);
        moved.target += extent * glam::Vec3::new(-0.05, 0.0, 0.03);
        moved
    }
}
