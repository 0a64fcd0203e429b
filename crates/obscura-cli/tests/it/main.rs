//! The integration tests of `obscura-cli`, one binary: each former `tests/NAME.rs` is the
//! module `NAME` (`tests/it/NAME.rs`). The error corpus stays in `tests/corpus`.

mod cli;
mod dataset;
mod ensure_vulkan;
mod path;
mod view;
