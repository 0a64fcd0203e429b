// Two-phase schedule, phase 1 (seed 000 §3.8, §3.9; docs/AUTHORS_CODE.md §1.3, §2.2): every sample
// from the first look of the source only. Samples the source still has to resolve
// (source_lookup(...) .trace) are flagged in a per-pixel bit mask and left out of the estimator's
// partial state, and the source is told (`source_request`: SD-SVAO marks the sample's pixel for the
// stochastic depth map); a pixel without flags is finished here.
// The partial state stays in 32-bit floats for phase 2 (no 8-bit quantisation between phases), and
// flagged pixels are appended to a work list (when COMPACT) for an indirect phase 2.

@group(GROUP_SCHEDULE) @binding(SCHEDULE_PIXELS) var<storage, read_write> two_phase_pixels: array<TwoPhasePixel>;
@group(GROUP_SCHEDULE) @binding(SCHEDULE_WORK_LIST) var<storage, read_write> work: WorkList;

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
        group_base = atomicAdd(&work.count, atomicLoad(&group_count));
    }
    workgroupBarrier();
    if (COMPACT && flagged) {
        work.items[group_base + slot] = index;
    }
}

// Phase 1 for one pixel; true when some of its samples need the source.
fn shade(id: vec2<u32>, index: u32) -> bool {
    if (any(id >= view.visible_size)) {
        return false;
    }
    var out: TwoPhasePixel;
    out.mask = 0u;
    let p = estimator_pixel(id);
    if (!estimator_pixel_valid(p)) {
        two_phase_pixels[index] = out;
        textureStore(ao_out, id, vec4<f32>(1.0));
        return false;
    }
    var acc = estimator_accum_init();
    // A variable of its own: naga 30's SPIR-V writer fails on a pointer to a struct member as an
    // argument.
    var mask = 0u;
    // Written out as one call per sample (schedules::write_out_sample_loop).
    for (var i = 0u; i < SAMPLE_COUNT; i++) {
        phase_1_sample(p, i, &acc, &mask);
    }
    out.mask = mask;
    out.accum = acc;
    two_phase_pixels[index] = out;
    if (out.mask == 0u) {
        textureStore(ao_out, id, vec4<f32>(estimator_finish(p, acc)));
    }
    return out.mask != 0u;
}

// Sample `i` of phase 1: its value into `acc`, or its bit into `mask` and its request to the
// source.
fn phase_1_sample(p: EstimatorPixel, i: u32, acc: ptr<function, EstimatorAccum>, mask: ptr<function, u32>) {
    let s = estimator_sample(p, i);
    if (!estimator_sample_active(s)) {
        return;
    }
    *acc = estimator_accum_sample(*acc, s);
    let l = source_lookup(p, s);
    if (l.trace) {
        *mask |= 1u << i;
        source_request(l);
    } else {
        *acc = estimator_accum_value(*acc, s, l.value);
    }
}
