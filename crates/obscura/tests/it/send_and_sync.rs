//! Engines keep obscura's per-view state in their render worlds, whose resources must be Send
//! and Sync (Bevy's; crates/bevy_obscura). A compile-time check: this file stops building when a
//! field breaks it.

#[test]
fn the_types_an_engine_keeps_are_send_and_sync() {
    fn check<T: Send + Sync>() {}
    check::<obscura::Gpu>();
    check::<obscura::AmbientOcclusion>();
    check::<obscura::EngineInput>();
    check::<obscura::EngineGeometry>();
    check::<obscura::Renderer>();
}
