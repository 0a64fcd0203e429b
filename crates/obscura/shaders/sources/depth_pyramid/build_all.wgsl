// The whole depth pyramid in one dispatch (seed 004 §3.3; the per-level build.wgsl otherwise):
// each workgroup owns one texel of the top level L − 1, the K^(L−1) × K^(L−1) pixels below it,
// and builds every level of that tile in workgroup memory, level by level with a barrier between,
// writing each level's texels as it goes. The same means as build.wgsl: the mean of the K × K
// texels below, background (0, and whatever lies past a level's edge) left out. Used where the
// tile's levels fit the workgroup memory (src/sources/depth_pyramid.rs decides).

struct PyramidTiles {
    // Level l's size in texels (x, y) for l < 8 (level 0: the framebuffer).
    sizes: array<vec4<u32>, 8>,
    factor: u32,
    levels: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var<uniform> tiles: PyramidTiles;
@group(0) @binding(1) var depth: texture_2d<f32>;
@group(0) @binding(2) var out: texture_storage_2d_array<r32float, write>;

// 16 KiB, WebGPU's guaranteed workgroup memory: levels 1 … L − 1 of one tile.
const TILE_FLOATS: u32 = 4096u;
var<workgroup> tile: array<f32, TILE_FLOATS>;

const THREADS: u32 = 64u;

// The tile's width in texels of level l: K^(L − 1 − l).
fn tile_width(l: u32) -> u32 {
    var w = 1u;
    for (var i = l + 1u; i < tiles.levels; i++) {
        w *= tiles.factor;
    }
    return w;
}

// Where level l's texels start in `tile`.
fn tile_offset(l: u32) -> u32 {
    var offset = 0u;
    for (var k = 1u; k < l; k++) {
        let w = tile_width(k);
        offset += w * w;
    }
    return offset;
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) thread: u32) {
    let k = tiles.factor;
    for (var l = 1u; l < tiles.levels; l++) {
        let w = tile_width(l);
        let offset = tile_offset(l);
        let below_offset = tile_offset(l - 1u);
        let below_w = w * k;
        let size = tiles.sizes[l].xy;
        for (var i = thread; i < w * w; i += THREADS) {
            let local = vec2<u32>(i % w, i / w);
            let texel = group.xy * w + local;
            var sum = 0.0;
            var count = 0.0;
            for (var y = 0u; y < k; y++) {
                for (var x = 0u; x < k; x++) {
                    var z = 0.0;
                    if (l == 1u) {
                        let pixel = texel * k + vec2<u32>(x, y);
                        if (all(pixel < tiles.sizes[0].xy)) {
                            z = textureLoad(depth, pixel, 0).r;
                        }
                    } else {
                        let child = local * k + vec2<u32>(x, y);
                        z = tile[below_offset + child.y * below_w + child.x];
                    }
                    if (z > 0.0) {
                        sum += z;
                        count += 1.0;
                    }
                }
            }
            var mean = 0.0;
            if (count > 0.0 && all(texel < size)) {
                mean = sum / count;
            }
            tile[offset + i] = mean;
            if (all(texel < size)) {
                textureStore(out, texel, l - 1u, vec4<f32>(mean));
            }
        }
        workgroupBarrier();
    }
}
