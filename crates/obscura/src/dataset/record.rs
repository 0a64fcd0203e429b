//! What a dataset writes about itself: the spec's canonical form and hash, the manifest line of
//! a view, the JSON of cameras and settings. Every record that must be the same on every run is
//! made here from data only (no clock, no host, no path outside the output folder).

use super::spec::{CameraSource, Channel, Spec, Tracer};
use crate::reference::ground_truth::ReferenceSettings;
use crate::scene::Camera;
use serde_json::{json, Value};
use sha2::{Digest, Sha256};

/// The version of obscura that writes a dataset (every manifest line and `dataset.json`).
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// SHA-256 of `bytes`, lower-case hex.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// The truth's settings as recorded (`seed` the view's own).
pub fn truth_record(t: &ReferenceSettings, tracer: &str) -> Value {
    json!({
        "model": t.model.name(),
        "spp": t.reported_spp(),
        "radius": t.vao.radius,
        "falloff": t.falloff,
        "seed": t.seed,
        "vao": serde_json::to_value(t.vao).expect("VAO settings serialise"),
        "tracer": tracer,
    })
}

/// A camera as recorded: eye, target, up, vertical field of view (degrees), near plane.
pub fn camera_record(c: &Camera, near: f32) -> Value {
    json!({
        "eye": c.eye.to_array(),
        "target": c.target.to_array(),
        "up": c.up.to_array(),
        "fov_y_deg": c.fov_y_deg,
        "near": near,
    })
}

/// Every resolved value of `spec` (scene sources as given, settings with their defaults and
/// units applied): the spec's identity ([`Spec::hash`]).
pub fn canonical_spec(spec: &Spec) -> Value {
    let scenes: Vec<Value> = spec
        .scenes
        .iter()
        .map(|s| {
            let cameras = match &s.cameras {
                CameraSource::Random {
                    min_coverage,
                    clearance,
                } => json!({"random": {"min_coverage": min_coverage, "clearance": clearance}}),
                CameraSource::Scene => json!("scene"),
                CameraSource::Path(name) => json!({ "path": name }),
            };
            let rows: serde_json::Map<String, Value> = s
                .rows
                .iter()
                .map(|r| {
                    let v = serde_json::to_value(r).expect("settings serialise");
                    (r.technique.name().to_string(), v)
                })
                .collect();
            json!({
                "source": s.source,
                "allow_outside_files": s.allow_outside_files,
                "units_per_metre": s.units_per_metre,
                "sides": s.sidedness.name(),
                "normals": s.normals.name(),
                "views": s.views,
                "cameras": cameras,
                "fov": s.fov,
                "rows": rows,
                "truth": truth_record(&s.truth, spec.tracer.name()),
            })
        })
        .collect();
    json!({
        "seed": spec.seed,
        "size": [spec.width, spec.height],
        "guard_band": spec.guard_band(),
        "views_per_shard": spec.views_per_shard,
        "format": spec.format.extension(),
        "store": spec.store.iter().map(|c| c.name()).collect::<Vec<_>>(),
        "scenes": scenes,
    })
}

/// The arrays a view file of `spec` holds, in order.
pub fn array_names(spec: &Spec) -> Vec<String> {
    spec.store.iter().map(|c| c.array_name()).collect()
}

/// Whether `spec` stores the truth.
pub fn stores_truth(spec: &Spec) -> bool {
    spec.store.contains(&Channel::Truth)
}

/// The tracer's name as recorded: the one that ran (`auto` resolved).
pub fn tracer_name(tracer: Tracer, on_cpu: bool) -> &'static str {
    match (tracer, on_cpu) {
        (Tracer::Auto, true) | (Tracer::Cpu, _) => "cpu",
        _ => "gpu",
    }
}
