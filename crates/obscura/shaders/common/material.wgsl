// Materials as the G-buffer and the ray tracer see them (mirrors GpuMaterial in
// src/raster/gpu_scene.rs), and the one alpha lookup both use: nearest texel, repeat, LOD 0 —
// exactly `Texture::alpha_at` on the CPU.

struct Material {
    base_color: vec4<f32>,
    // Texture array layer, or -1 for none.
    texture_layer: i32,
    // Alpha-test cutoff, or -1 when the material is not alpha-tested.
    alpha_cutoff: f32,
    texture_size: vec2<u32>,
    // Bit 0: back faces count (double-sided or alpha-tested).
    flags: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// Base colour texel (raw, sRGB-encoded rgb) under `uv`, or opaque white without a texture.
fn material_texel(m: Material, textures: texture_2d_array<f32>, uv: vec2<f32>) -> vec4<f32> {
    if (m.texture_layer < 0) {
        return vec4<f32>(1.0);
    }
    let f = uv - floor(uv);
    let texel = min(vec2<u32>(f * vec2<f32>(m.texture_size)), m.texture_size - 1u);
    return textureLoad(textures, texel, m.texture_layer, 0);
}

// Whether a surface point passes the material's alpha test (always for opaque materials).
fn material_passes_alpha(m: Material, textures: texture_2d_array<f32>, uv: vec2<f32>) -> bool {
    if (m.alpha_cutoff < 0.0) {
        return true;
    }
    return m.base_color.a * material_texel(m, textures, uv).a >= m.alpha_cutoff;
}
