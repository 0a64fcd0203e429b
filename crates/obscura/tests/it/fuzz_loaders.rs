//! Structure-aware fuzzing of the scene loaders and the BVH build on stable Rust (issue 15):
//! valid glTF, GLB and OBJ files are mutated (byte flips, truncation, spliced spans, JSON field
//! mutation, face-index mutation) and loaded; every result must be `Ok` or a clean `Err`: no panic
//! and no input that takes more than 10 s. Findings are written to `$OBSCURA_FUZZ_FINDINGS`
//! (default: a temporary folder) so they can become corpus files.
//!
//! Runs for `$OBSCURA_FUZZ_SECONDS` (default 30: the CI run); RELIABILITY.md records the long run.
//! A self-contained mutator rather than `proptest`/`arbitrary`: the inputs are whole files whose
//! structure (JSON tree, GLB chunks, OBJ face lines) the mutations must know, which neither crate
//! models, and a seeded loop reproduces any finding from its iteration number.

use obscura::bvh::Bvh;
use serde_json::Value;
use std::cell::Cell;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use std::sync::Once;
use std::time::{Duration, Instant};

/// SplitMix64 (Steele, Lea, Flood 2014): a seeded stream, so iteration `i` is reproducible.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

fn png_4x4() -> Vec<u8> {
    let img = image::RgbaImage::from_fn(4, 4, |x, y| {
        image::Rgba([60 * x as u8, 60 * y as u8, 90, 80 * ((x + y) % 4) as u8])
    });
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

/// The binary buffer of the seed glTF: a quad (positions, normals, uvs, u16 indices) and a
/// triangle (positions only).
fn seed_buffer() -> Vec<u8> {
    let f = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let mut b = f(&[0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.]); // 0: 48 positions
    b.extend(f(&[0., 0., 1., 0., 0., 1., 0., 0., 1., 0., 0., 1.])); // 48: 48 normals
    b.extend(f(&[0., 1., 1., 1., 1., 0., 0., 0.])); // 96: 32 uvs
    b.extend([0u16, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes())); // 128: 12 indices
    b.extend(f(&[0., 0., 0., 2., 0., 0., 0., 2., 1.])); // 140: 36 triangle
    b
}

/// The seed glTF's JSON; `buffer` is its `buffers[0]` entry, `image` its `images[0]` entry.
fn seed_json(buffer: Value, image: Value) -> Value {
    serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0, 2, 3]}],
        "nodes": [
            {"translation": [1, 0, 0], "rotation": [0, 0.38268343, 0, 0.9238795], "children": [1]},
            {"mesh": 0, "scale": [2, 1, 0.5]},
            {"mesh": 1, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,3,0,1]},
            {"camera": 0, "translation": [0, 1, 6]}
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
        "meshes": [
            {"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                             "indices": 3, "material": 0}]},
            {"primitives": [{"attributes": {"POSITION": 4}, "material": 1, "mode": 4}]}
        ],
        "materials": [
            {"alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": true,
             "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "baseColorTexture": {"index": 0}}},
            {"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.6, 1]}}
        ],
        "textures": [{"source": 0}],
        "images": [image],
        "buffers": [buffer],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48},
            {"buffer": 0, "byteOffset": 48, "byteLength": 48},
            {"buffer": 0, "byteOffset": 96, "byteLength": 32},
            {"buffer": 0, "byteOffset": 128, "byteLength": 12},
            {"buffer": 0, "byteOffset": 140, "byteLength": 36}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"},
            {"bufferView": 4, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [2,2,1]}
        ]
    })
}

fn glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |v: &[u8], with: u8| {
        let mut v = v.to_vec();
        v.resize(v.len().div_ceil(4) * 4, with);
        v
    };
    let (json, bin) = (pad(json, b' '), pad(bin, 0));
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(&json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(&bin);
    out
}

const OBJ: &str = "mtllib seed.mtl\no quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\n\
vt 1 1\nvt 0 1\nvn 0 0 1\nusemtl leaf\nf 1/1/1 2/2/1 3/3/1 4/4/1\no tri\nv 0 0 1\nv 2 0 1\nv 0 2 1\n\
usemtl plain\nf -3 -2 -1\n";
const MTL: &str = "newmtl leaf\nKd 1 1 1\nmap_Kd seed.png\nnewmtl plain\nKd 0.2 0.4 0.6\nd 0.5\n";

/// The seed files: (extension, bytes); the OBJ's `.mtl` and texture sit beside it.
fn seeds() -> Vec<(&'static str, Vec<u8>)> {
    let png = png_4x4();
    let bin = seed_buffer();
    let embedded = seed_json(
        serde_json::json!({"byteLength": bin.len(), "uri": format!("data:application/octet-stream;base64,{}", base64::encode(&bin))}),
        serde_json::json!({"uri": format!("data:image/png;base64,{}", base64::encode(&png))}),
    );
    // GLB: the image in a buffer view after the geometry.
    let mut glb_bin = bin.clone();
    let image_offset = glb_bin.len();
    glb_bin.extend(&png);
    let mut glb_json = seed_json(
        serde_json::json!({"byteLength": glb_bin.len()}),
        serde_json::json!({"bufferView": 5, "mimeType": "image/png"}),
    );
    glb_json["bufferViews"].as_array_mut().unwrap().push(
        serde_json::json!({"buffer": 0, "byteOffset": image_offset, "byteLength": png.len()}),
    );
    vec![
        ("gltf", serde_json::to_vec(&embedded).unwrap()),
        (
            "glb",
            glb(&serde_json::to_vec(&glb_json).unwrap(), &glb_bin),
        ),
        ("obj", OBJ.as_bytes().to_vec()),
    ]
}

const HOSTILE_NUMBERS: [f64; 14] = [
    0.0,
    1.0,
    2.0,
    3.0,
    4.0,
    5.0,
    -1.0,
    0.5,
    255.0,
    5123.0,
    65535.0,
    4294967295.0,
    4294967296.0,
    1e30,
];

/// Replaces a random node of the JSON tree (or deletes a key, or duplicates an array element):
/// walks down a random path, stopping with probability 1/3 at each container.
fn mutate_json(v: &mut Value, rng: &mut Rng) {
    let go_deeper = rng.below(3) != 0;
    match v {
        Value::Object(map) if !map.is_empty() && go_deeper => {
            let key = rng.pick(&map.keys().cloned().collect::<Vec<_>>()).clone();
            if rng.below(8) == 0 {
                map.remove(&key);
            } else {
                mutate_json(map.get_mut(&key).unwrap(), rng);
            }
            return;
        }
        Value::Array(items) if !items.is_empty() && go_deeper => {
            let i = rng.below(items.len());
            if rng.below(8) == 0 {
                let copy = items[i].clone();
                items.push(copy);
            } else {
                mutate_json(&mut items[i], rng);
            }
            return;
        }
        _ => {}
    }
    *v = match rng.below(7) {
        0..=2 => serde_json::json!(*rng.pick(&HOSTILE_NUMBERS)),
        3 => Value::Null,
        4 => serde_json::json!("x"),
        5 => serde_json::json!([]),
        _ => serde_json::json!({}),
    };
}

/// Replaces one face index of an OBJ with a hostile one.
fn mutate_obj_index(text: &str, rng: &mut Rng) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let faces: Vec<usize> = (0..lines.len())
        .filter(|&i| lines[i].starts_with("f "))
        .collect();
    let line = *rng.pick(&faces);
    let mut fields: Vec<String> = lines[line].split(' ').map(str::to_owned).collect();
    let field = 1 + rng.below(fields.len().saturating_sub(1));
    if field >= fields.len() {
        return text.to_owned();
    }
    let hostile = [
        "0",
        "-1",
        "-100",
        "99",
        "2147483648",
        "-2147483649",
        "1e3",
        "",
        "/",
        "1//",
        "x",
    ];
    fields[field] = rng.pick(&hostile).to_string();
    lines[line] = fields.join(" ");
    lines.join("\n")
}

/// One mutation of `bytes` (a seed of kind `ext`), chosen by `rng`.
fn mutate(ext: &str, bytes: &[u8], rng: &mut Rng) -> Vec<u8> {
    let mut out = bytes.to_vec();
    match rng.below(6) {
        // Byte flips.
        0 => {
            for _ in 0..1 + rng.below(8) {
                let i = rng.below(out.len());
                out[i] = rng.next() as u8;
            }
        }
        // Truncation.
        1 => out.truncate(rng.below(out.len())),
        // A span deleted or duplicated.
        2 => {
            let (a, len) = (rng.below(out.len()), 1 + rng.below(64));
            let b = (a + len).min(out.len());
            if rng.below(2) == 0 {
                out.drain(a..b);
            } else {
                let span = out[a..b].to_vec();
                let at = rng.below(out.len());
                out.splice(at..at, span);
            }
        }
        // Structure: JSON fields (glTF, GLB's JSON chunk) or OBJ face indices, where an
        // earlier mutation left the structure readable; otherwise a byte flip.
        _ => match structured(ext, bytes, rng) {
            Some(mutated) => out = mutated,
            None => {
                let i = rng.below(out.len());
                out[i] ^= 0x20;
            }
        },
    }
    out
}

fn structured(ext: &str, bytes: &[u8], rng: &mut Rng) -> Option<Vec<u8>> {
    match ext {
        "gltf" => {
            let mut v: Value = serde_json::from_slice(bytes).ok()?;
            for _ in 0..1 + rng.below(3) {
                mutate_json(&mut v, rng);
            }
            serde_json::to_vec(&v).ok()
        }
        "glb" => {
            let len = u32::from_le_bytes(bytes.get(12..16)?.try_into().ok()?) as usize;
            let mut v: Value = serde_json::from_slice(bytes.get(20..20 + len)?).ok()?;
            let bin = bytes.get(20 + len + 8..)?;
            for _ in 0..1 + rng.below(3) {
                mutate_json(&mut v, rng);
            }
            Some(glb(&serde_json::to_vec(&v).ok()?, bin))
        }
        _ => {
            let text = std::str::from_utf8(bytes).ok()?;
            text.lines()
                .any(|l| l.starts_with("f "))
                .then(|| mutate_obj_index(text, rng).into_bytes())
        }
    }
}

/// Loads `path` and, when it loads, builds its BVH and asks for its extent and camera. Whether
/// it loaded.
fn exercise(path: &Path) -> bool {
    let Ok(scene) = obscura::scene::load(path.to_str().unwrap()) else {
        return false;
    };
    let bvh = Bvh::build(&scene);
    assert!(
        bvh.max_depth() <= 64,
        "BVH depth {} over the GPU stack",
        bvh.max_depth()
    );
    let _ = scene.check_extent();
    let _ = scene.default_camera(1.5).validate();
    true
}

/// Runs `f` with this thread's panic messages kept off the log. The panic hook is the process's,
/// shared with the other tests of the binary (tests/it): it stays silent only on the thread in
/// `f`, and passes every other panic to the hook it replaced.
fn quietly<T>(f: impl FnOnce() -> T) -> T {
    thread_local!(static QUIET: Cell<bool> = const { Cell::new(false) });
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !QUIET.with(Cell::get) {
                previous(info);
            }
        }));
    });
    QUIET.with(|q| q.set(true));
    let out = f();
    QUIET.with(|q| q.set(false));
    out
}

#[test]
fn mutated_scene_files_load_or_fail_cleanly() {
    let seconds: u64 = std::env::var("OBSCURA_FUZZ_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(30);
    let base_seed: u64 = std::env::var("OBSCURA_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let work = tempfile::tempdir().unwrap();
    let findings = std::env::var_os("OBSCURA_FUZZ_FINDINGS")
        .map_or_else(|| work.path().join("findings"), Into::into);
    std::fs::create_dir_all(&findings).unwrap();
    std::fs::write(work.path().join("seed.mtl"), MTL).unwrap();
    std::fs::write(work.path().join("seed.png"), png_4x4()).unwrap();
    let seeds = seeds();
    // The seeds themselves load.
    for (ext, bytes) in &seeds {
        let path = work.path().join(format!("seed.{ext}"));
        std::fs::write(&path, bytes).unwrap();
        let scene = obscura::scene::load(path.to_str().unwrap()).unwrap();
        assert!(scene.triangle_count() >= 3, "{ext} seed");
    }
    let start = Instant::now();
    let (mut inputs, mut loaded, mut failures) = (0u64, 0u64, Vec::new());
    let mut slowest = Duration::ZERO;
    while start.elapsed() < Duration::from_secs(seconds) {
        let iteration = inputs;
        let mut rng = Rng(base_seed.wrapping_mul(0x1000_0000_01b3) ^ iteration);
        let (ext, seed) = rng.pick(&seeds);
        // Up to three stacked mutations.
        let mut bytes = seed.clone();
        for _ in 0..1 + rng.below(3) {
            if bytes.is_empty() {
                break;
            }
            bytes = mutate(ext, &bytes, &mut rng);
        }
        let path = work.path().join(format!("case.{ext}"));
        std::fs::write(&path, &bytes).unwrap();
        let t = Instant::now();
        // A panic here is a finding, reported below: keep it off the test log.
        let outcome = quietly(|| catch_unwind(AssertUnwindSafe(|| exercise(&path))));
        let took = t.elapsed();
        slowest = slowest.max(took);
        loaded += u64::from(matches!(outcome, Ok(true)));
        if outcome.is_err() || took > Duration::from_secs(10) {
            let name = format!("finding-{base_seed}-{iteration}.{ext}");
            std::fs::write(findings.join(&name), &bytes).unwrap();
            failures.push(format!(
                "{name}: {}",
                if outcome.is_err() {
                    "panic"
                } else {
                    "over 10 s"
                }
            ));
        }
        inputs += 1;
    }
    println!(
        "fuzz: {inputs} inputs in {:.0} s (seed {base_seed}), {loaded} loaded, slowest {:.4} s, \
         {} findings",
        start.elapsed().as_secs_f64(),
        slowest.as_secs_f64(),
        failures.len()
    );
    assert!(inputs > 100, "only {inputs} inputs");
    assert!(
        failures.is_empty(),
        "{} inputs panicked or hung (saved in {}): {failures:?}",
        failures.len(),
        findings.display()
    );
}
