// Vertex (shading) normals: the octahedral encoding of `encode_normal` in src/raster/gpu_scene.rs
// (Cigolle et al., "A Survey of Efficient Representations for Independent Unit Vectors", JCGT 3(2),
// 2014), stored in the .zw of the scene's per-vertex attributes next to the uv; x > 1.5 marks a
// vertex without a normal. The CPU twin of the orientation rule is Scene::surface_normal.

// The unit normal encoded in `e`, or zero where the vertex has none.
fn decode_vertex_normal(e: vec2<f32>) -> vec3<f32> {
    if (e.x > 1.5) {
        return vec3<f32>(0.0);
    }
    var n = vec3<f32>(e, 1.0 - abs(e.x) - abs(e.y));
    let t = max(-n.z, 0.0);
    n.x += select(t, -t, n.x >= 0.0);
    n.y += select(t, -t, n.y >= 0.0);
    return normalize(n);
}

// The octahedral encoding of unit `n` (the twin of `encode_normal` in src/raster/gpu_scene.rs),
// which decode_vertex_normal turns back; the temporal accumulation stores its history's normals
// so.
fn encode_octahedral(n: vec3<f32>) -> vec2<f32> {
    let p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    if (n.z >= 0.0) {
        return p;
    }
    let sign = select(vec2<f32>(-1.0), vec2<f32>(1.0), p >= vec2<f32>(0.0));
    return (vec2<f32>(1.0) - abs(p.yx)) * sign;
}

// The interpolated vertex normal `shading` (any length) turned to the side of the unit face
// normal `face`; `face` itself where `shading` is zero (a vertex without a normal).
fn oriented_shading_normal(shading: vec3<f32>, face: vec3<f32>) -> vec3<f32> {
    let len = length(shading);
    if (!(len > 0.0)) {
        return face;
    }
    let n = shading / len;
    return select(n, -n, dot(n, face) < 0.0);
}
