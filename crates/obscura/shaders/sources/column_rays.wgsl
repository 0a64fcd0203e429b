// Hidden-depth source "column rays" (`rt-vao`, `rt-svao`, seed 000 §3.6): the depth buffer first;
// samples it cannot decide (occluded, or off-screen) trace their camera ray past the depth-buffer
// hit (column_trace.wgsl). The source contract: see first_layer.wgsl.

fn source_lookup(p: VaoPixel, s: VaoSample) -> DepthLookup {
    let f = p.frame;
    let c = s.column;
    var l: DepthLookup;
    l.value = c.start - c.end;
    l.trace = false;
    let cell = floor(c.px);
    l.px = cell + 0.5;
    l.t_after = 0.0;
    if (all(cell == vec2<f32>(f.pixel))) {
        return l; // snaps to the shading pixel itself: fully visible
    }
    let inside = all(cell >= vec2<f32>(0.0)) && all(cell < vec2<f32>(view.full_size));
    if (!inside) {
        // Off-screen: no depth-buffer sample; trace the whole interval.
        l.trace = true;
        return l;
    }
    let sample_pixel = vec2<u32>(cell);
    let z = textureLoad(depth_tex, sample_pixel, 0).r;
    if (is_background(z)) {
        return l;
    }
    let occluder = pixel_to_view(view, l.px, z);
    let height = column_height(f, c, occluder);
    l.value = column_visibility(halo_start(f), height, c.start, c.end);
    // Surfaces beyond the first one lie lower along the column when the height falls with the ray
    // parameter (the usual case): then they can only lower the visibility when the first surface
    // is occluded — beyond the constant area (in it the visibility is already 0). Where the
    // tangent-plane correction makes the height rise with depth, any first surface may hide a
    // lower visibility, so the ray is traced.
    let rising = column_height_slope(f, pixel_to_view(view, l.px, 1.0)) > 0.0;
    l.trace = l.value > 0.0 && (rising || height > halo_start(f));
    // Past the depth-buffer hit (relative slack, as the authors' 0.01 R offset).
    l.t_after = z * (1.0 + 1e-5);
    return l;
}

// The visibility of a sample `source_lookup` flagged: its camera ray traced.
fn source_resolve(p: VaoPixel, s: VaoSample, l: DepthLookup) -> f32 {
    return trace_column_visibility(p.frame, s.column, l.px, l.t_after, l.value);
}

// Two-phase phase 1: rays need nothing prepared.
fn source_request(l: DepthLookup) {}
