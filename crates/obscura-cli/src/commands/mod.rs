pub mod bench;
pub mod compare;
pub mod demo;
pub mod diff;
pub mod info;
pub mod reference;
pub mod render;
pub mod scenes;
