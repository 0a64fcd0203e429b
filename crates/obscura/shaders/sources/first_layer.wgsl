// Hidden-depth source "first layer" (`vao`): nothing behind the first depth layer is known, so a
// sample's value is what the first layer says (frame.wgsl's first_layer_lookup), and the estimator's
// own model (VAO: the thickness/halo model, seed 000 §3.3, §3.5) stands in for what is hidden.
//
// The source contract (docs/ARCHITECTURE.md): source_lookup (first look; `trace` = resolve later),
// source_resolve (the value after consulting hidden depths), source_request (two-phase phase 1:
// prepare what source_resolve will read).

fn source_lookup(p: EstimatorPixel, s: EstimatorSample) -> DepthLookup {
    var l = first_layer_lookup(p, s);
    l.trace = false;
    return l;
}

fn source_resolve(p: EstimatorPixel, s: EstimatorSample, l: DepthLookup) -> EstimatorValue {
    return l.value;
}

fn source_request(l: DepthLookup) {}
