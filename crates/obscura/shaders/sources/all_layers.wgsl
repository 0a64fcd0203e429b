// Hidden-depth source "all layers", for the `vao` ground truth only (shaders/reference/reference.wgsl): no
// depth buffer at all; every sample that leaves its shading pixel traces its camera-ray column
// from the near plane through every surface (column_trace.wgsl), so the result is the VAO model
// with nothing hidden (src/reference/ground_truth.rs mirrors it on the CPU).

fn source_lookup(p: VaoPixel, s: VaoSample) -> DepthLookup {
    var l: DepthLookup;
    l.value = s.column.start - s.column.end;
    let cell = floor(s.column.px);
    l.px = cell + 0.5;
    l.t_after = 0.0;
    l.trace = any(cell != vec2<f32>(p.frame.pixel));
    return l;
}

fn source_resolve(p: VaoPixel, s: VaoSample, l: DepthLookup) -> f32 {
    return trace_column_visibility(p.frame, s.column, l.px, l.t_after, l.value);
}

fn source_request(l: DepthLookup) {}
