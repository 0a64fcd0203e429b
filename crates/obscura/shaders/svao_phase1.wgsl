// Stenciled VAO, phase 1 (seed 000 §3.8, §3.9; seed-code-notes §1.3, §2.2): every sample from the
// depth buffer only. Samples the hidden-depth source still has to resolve (depth_lookup(...).trace)
// are flagged in a per-pixel bit mask and left out of the sum, and the source is told
// (`request_hidden`: SD-SVAO marks the sample's pixel for the stochastic depth map); a pixel
// without flags is finished here.
// The partial sums stay in 32-bit floats for phase 2 (no 8-bit quantisation between phases), and
// flagged pixels are appended to a work list (when COMPACT) for an indirect phase 2.

@group(2) @binding(0) var<storage, read_write> svao_pixels: array<SvaoPixel>;
@group(2) @binding(1) var<storage, read_write> work_count: atomic<u32>;
@group(2) @binding(2) var<storage, read_write> work_list: array<u32>;

// Work-list compaction per workgroup: flagged pixels take consecutive local slots, then one
// global atomic reserves the workgroup's range, so the list keeps each 32x8 tile together (phase 2
// threads then trace neighbouring pixels) and costs one global atomic per workgroup.
var<workgroup> group_count: atomic<u32>;
var<workgroup> group_base: u32;

@compute @workgroup_size(32, 8)
fn main(@builtin(global_invocation_id) global_id: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    if (local == 0u) {
        atomicStore(&group_count, 0u);
    }
    workgroupBarrier();
    let id = global_id.xy;
    let index = id.y * view.visible_size.x + id.x;
    let flagged = shade(id, index);
    var slot = 0u;
    if (COMPACT && flagged) {
        slot = atomicAdd(&group_count, 1u);
    }
    workgroupBarrier();
    if (COMPACT && local == 0u) {
        group_base = atomicAdd(&work_count, atomicLoad(&group_count));
    }
    workgroupBarrier();
    if (COMPACT && flagged) {
        work_list[group_base + slot] = index;
    }
}

// Phase 1 for one pixel; true when some of its samples need rays.
fn shade(id: vec2<u32>, index: u32) -> bool {
    if (any(id >= view.visible_size)) {
        return false;
    }
    var out: SvaoPixel;
    out.mask = 0u;
    let p = vao_pixel(id);
    if (!p.valid) {
        svao_pixels[index] = out;
        textureStore(ao_out, id, vec4<f32>(1.0));
        return false;
    }
    var sum = 0.0;
    var clipped_sum = 0.0;
    for (var i = 0u; i < SAMPLE_COUNT; i++) {
        let s = vao_sample(p, i);
        if (s.h == 0.0) {
            continue;
        }
        let inv_2h = 0.5 / s.h;
        clipped_sum += (s.column.start - s.column.end) * inv_2h;
        let l = depth_lookup(p.frame, s.column);
        if (l.trace) {
            out.mask |= 1u << i;
            request_hidden(l);
        } else {
            sum += l.free * inv_2h;
        }
    }
    out.sum = sum;
    out.clipped_sum = clipped_sum;
    svao_pixels[index] = out;
    if (out.mask == 0u) {
        textureStore(ao_out, id, vec4<f32>(vao_finish(sum, clipped_sum)));
    }
    return out.mask != 0u;
}
