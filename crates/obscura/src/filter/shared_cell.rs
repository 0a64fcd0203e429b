//! A `Cell` that is Sync: the per-frame state filters change through `&self` (the previous
//! camera, the frame number, the ray budget), behind a mutex so that an `AmbientOcclusion` can
//! be shared with an engine's render thread (Bevy's render world needs Send + Sync). Only ever
//! locked for a copy in or out, so never contended for long.

use std::sync::Mutex;

/// `get` and `set` of a `Copy` value through a shared reference.
#[derive(Debug, Default)]
pub(crate) struct SharedCell<T: Copy>(Mutex<T>);

impl<T: Copy> SharedCell<T> {
    pub fn new(value: T) -> Self {
        Self(Mutex::new(value))
    }

    pub fn get(&self) -> T {
        // A panic elsewhere cannot leave a `Copy` value half written: take it anyway.
        *self.0.lock().unwrap_or_else(|e| e.into_inner())
    }

    pub fn set(&self, value: T) {
        *self.0.lock().unwrap_or_else(|e| e.into_inner()) = value;
    }
}
