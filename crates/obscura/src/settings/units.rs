//! A scene's unit of length, as users name it (`--units`, a dataset spec's `units`).

/// World units per metre for a unit given as its length in metres (`0.01`) or by name (m, cm,
/// mm, km, in, ft); `None` for anything else, zero, negative or not finite. Computed in f64 so
/// that `0.001` gives exactly 1000.
pub fn units_per_metre(units: &str) -> Option<f32> {
    let metres: f64 = match units.trim() {
        "m" => 1.0,
        "cm" => 0.01,
        "mm" => 0.001,
        "km" => 1000.0,
        "in" => 0.0254,
        "ft" => 0.3048,
        number => number.parse().unwrap_or(f64::NAN),
    };
    let per_metre = (1.0 / metres) as f32;
    (metres > 0.0 && per_metre.is_finite() && per_metre > 0.0).then_some(per_metre)
}
