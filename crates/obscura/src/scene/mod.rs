//! TEMPORARY stand-in until the scene module lands.
mod types;
pub use types::*;

impl Camera {
    pub fn view_matrix(&self) -> glam::Mat4 {
        glam::camera::rh::view::look_at_mat4(self.eye, self.target, self.up)
    }
}
