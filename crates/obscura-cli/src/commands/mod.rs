pub mod bench;
pub mod demo;
pub mod info;
pub mod render;
pub mod scenes;
