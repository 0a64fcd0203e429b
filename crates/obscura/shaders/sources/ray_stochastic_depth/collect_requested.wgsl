// Entry point of the ray-traced map's collection (collect.wgsl) where only the texels phase 1
// requested are traced (the two-phase rows), ours: each workgroup takes a 16×16 tile of texels,
// one invocation per texel, and packs the requested ones into its first invocations, so that
// warps trace together. About half of the texels are requested, in patches; a lane per texel in
// place left many lanes of a warp idle while the others traced (BENCHMARKS.md, H200: Sponza's
// map 10 % faster at 1/4 resolution and 16 % at 1/1, stairs' 6 % slower). Each texel is traced
// as before: the same map.

const TILE: u32 = 16u;
var<workgroup> tile_texels: array<u32, 256>; // TILE * TILE
var<workgroup> tile_count: atomic<u32>;

@compute @workgroup_size(256)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    if (local == 0u) {
        atomicStore(&tile_count, 0u);
    }
    workgroupBarrier();
    let origin = group.xy * TILE;
    let t = origin + vec2<u32>(local % TILE, local / TILE);
    if (all(t < params.map_size) && sd_request[t.y * params.map_size.x + t.x] != 0u) {
        tile_texels[atomicAdd(&tile_count, 1u)] = local;
    }
    // workgroupUniformLoad: the count as a value every invocation agrees on (after a barrier).
    let listed = workgroupUniformLoad(&tile_count);
    if (local < listed) {
        let k = tile_texels[local];
        collect_texel(origin + vec2<u32>(k % TILE, k / TILE));
    }
}
