//! Filters applied to raw AO.

pub mod bilateral;
