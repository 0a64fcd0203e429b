// Two-phase schedule, phase 2 (seed 000 §3.8, §3.9): only the samples phase 1 flagged, resolved by
// the hidden-depth source (`source_resolve`: rays or the stochastic depth map), added to phase 1's
// partial state. Two ways to find the work (both kept for
// comparison): COMPACT reads phase 1's work list (dispatched indirectly, one thread per flagged
// pixel); otherwise one thread per visible pixel returns at once when its mask is empty.

@group(GROUP_SCHEDULE) @binding(SCHEDULE_PIXELS) var<storage, read> two_phase_pixels: array<TwoPhasePixel>;
@group(GROUP_SCHEDULE) @binding(SCHEDULE_WORK_LIST) var<storage, read> work: WorkListRead;

// Dispatches wider than the 65535-workgroup limit wrap into y rows of 65535 workgroups.
const ROW_THREADS: u32 = 65535u * 64u;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) global_id: vec3<u32>) {
    var index = global_id.x + global_id.y * ROW_THREADS;
    if (COMPACT) {
        if (index >= work.count) {
            return;
        }
        index = work.items[index];
    } else if (index >= view.visible_size.x * view.visible_size.y) {
        return;
    }
    let stored = two_phase_pixels[index];
    if (stored.mask == 0u) {
        return;
    }
    let id = vec2<u32>(index % view.visible_size.x, index / view.visible_size.x);
    let p = estimator_pixel(id);
    var acc = stored.accum;
    var mask = stored.mask;
    while (mask != 0u) {
        let i = firstTrailingBit(mask);
        mask &= mask - 1u;
        let s = estimator_sample(p, i);
        let l = source_lookup(p, s);
        acc = estimator_accum_value(acc, s, source_resolve(p, s, l));
    }
    textureStore(ao_out, id, vec4<f32>(estimator_finish(p, acc)));
}
