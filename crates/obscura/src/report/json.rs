//! JSON encoding of the metric values: JSON cannot hold `±∞` or NaN, so a
//! non-finite `f64` is written as `null` (see the module docs of
//! [`super`] for how `null` reads back).

/// `f64` ⇄ number, non-finite ⇄ `null` (read back as NaN).
pub(super) mod finite_or_null {
    use serde::{Deserialize, Deserializer, Serializer};

    pub(in super::super) fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        // serde_json would already print `null` for non-finite values, but it
        // could not read it back, and other formats would do other things:
        // being explicit makes the rule part of the type.
        if v.is_finite() {
            s.serialize_f64(*v)
        } else {
            s.serialize_none()
        }
    }

    pub(in super::super) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
    }
}

/// As [`finite_or_null`], but `null` reads back as `+∞`: the PSNR of two
/// finite images is either finite or `+∞` (MSE = 0, an exact match), so that
/// is what a `null` PSNR means.
pub(super) mod psnr {
    use serde::{Deserialize, Deserializer, Serializer};

    pub(in super::super) fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        super::finite_or_null::serialize(v, s)
    }

    pub(in super::super) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::INFINITY))
    }
}
