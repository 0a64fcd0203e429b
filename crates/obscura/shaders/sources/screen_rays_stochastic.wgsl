// Screen rays over a stochastic depth map (`sd-hemisphere` over the rasterised map, seed 001
// §3.1; `ray-sd-hemisphere` over the ray-traced one, seed 002 §3.1; ours: the hemisphere march
// reads every layer a pixel stores, in the spirit of deep G-buffers, Mara et al. 2016). Preceded
// by the map's generated bindings and stochastic_depth/samples.wgsl (`sd_load`, `sd_near`).
//
// Each stored depth is a surface as thick as `hemisphere.thickness` or the gap to the next depth
// behind it, whichever is less, as the second layer bounds the first in screen_rays_dual.wgsl.
// So a march point is inside a surface exactly when the nearest surface at or in front of it
// lies less than its thickness in front: one pass over the pixel's depths, no sorting. The first
// layer keeps its tangent-plane test (screen_rays.wgsl); a stored depth has no normal, so its
// test is by depth alone. The map's facing is not stored: behind a closed object's back face
// the model assumes a thickness where there is air, as every depth-only model does (GTAO-VB over
// the same maps, seed 003).
//
// Off the framebuffer, in the map's own guard band (seed 002 §3.5), the map holds every layer,
// the visible one included: the march goes on there over the map's depths alone.

// The linear depth of the nearest stored depth at framebuffer pixel `pixel` at or in front of
// linear depth `zq` and behind linear depth `first` (the first layer; 0 in the band); 0 where
// none is. `first` matters for the ray-traced map at a resolution divisor: a texel's depths lie
// behind the first layer of the one pixel its ray went through, which may be nearer than this
// pixel's.
fn screen_rays_front_depth(pixel: vec2<i32>, first: f32, zq: f32) -> f32 {
    // Reversed Z (near / depth): at or in front of zq is at or above vq, nearest to it lowest;
    // behind `first` is below `v_first`.
    let vq = sd_near.x / zq;
    let v_first = select(3.0e38, sd_near.x / first, first > 0.0);
    var front = 3.0e38;
    for (var m = 0u; m < SD_MAPS; m++) {
        for (var k = 0u; k < SD_SAMPLES; k++) {
            let v = sd_load(m, pixel, k);
            if ((SD_COMPACT || SD_SORTED) && !(v > 0.0)) {
                break;
            }
            if (v >= vq && v < front && v < v_first) {
                front = v;
            }
        }
    }
    return select(0.0, sd_near.x / front, front < 3.0e38);
}

fn screen_rays_inside(q: vec3<f32>, cell: vec2<u32>, z: f32) -> bool {
    let zq = -q.z;
    // Both maps keep only depths behind the first layer (more than `peel_separation` behind it),
    // so a point in front of it needs no loads (most of a march's points).
    var front = 0.0;
    if (zq > z) {
        front = screen_rays_front_depth(vec2<i32>(cell), z, zq);
    }
    if (front > 0.0) {
        return zq - front < params.thickness;
    }
    // No stored depth between the first layer and q: the first layer's own test, its thickness
    // ending at the next stored depth (behind q here, so the test needs no bound).
    return hemisphere_inside(q, cell, z, params.thickness);
}

fn screen_rays_band_inside(q: vec3<f32>, pixel: vec2<i32>) -> i32 {
    if (!SD_HAS_GUARD_BAND || !sd_guard_covers(pixel)) {
        return -1;
    }
    let zq = -q.z;
    let front = screen_rays_front_depth(pixel, 0.0, zq);
    return select(0, 1, front > 0.0 && zq - front < params.thickness);
}
