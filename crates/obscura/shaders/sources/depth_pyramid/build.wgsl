// One level of the depth pyramid (seed 004 §3.3): every texel the mean linear depth of the K×K
// texels below it, background (0) left out; 0 where all of them are background. Level 1 reads the
// frame's depth, each further level the one before (a layer of the pyramid's array texture).
// One dispatch per level: a level needs all of the one below, and workgroups cannot wait for each
// other. Building every level of a tile in one workgroup instead (one dispatch, levels in
// workgroup memory: an 81×81-pixel tile at L = 5, K = 3) was measured slower on an H200, 0.035
// against 0.024 ms at 1080p + 64 and 0.58 ms at L = 2, where a tile is one texel (BENCHMARKS.md).

struct PyramidLevel {
    // The level below: its size in texels.
    below_size: vec2<u32>,
    // This level's size in texels.
    size: vec2<u32>,
    factor: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

@group(0) @binding(0) var<uniform> level: PyramidLevel;
@group(0) @binding(1) var below: texture_2d<f32>;
@group(0) @binding(2) var out: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (any(id.xy >= level.size)) {
        return;
    }
    let first = id.xy * level.factor;
    var sum = 0.0;
    var count = 0.0;
    for (var y = 0u; y < level.factor; y++) {
        for (var x = 0u; x < level.factor; x++) {
            let texel = first + vec2<u32>(x, y);
            if (any(texel >= level.below_size)) {
                continue;
            }
            let z = textureLoad(below, texel, 0).r;
            if (z > 0.0) {
                sum += z;
                count += 1.0;
            }
        }
    }
    textureStore(out, id.xy, vec4<f32>(select(0.0, sum / count, count > 0.0)));
}
