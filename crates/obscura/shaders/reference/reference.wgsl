// Ground-truth AO on the GPU, from the triangles (never from a depth buffer): the two models of
// src/reference/ground_truth.rs, through the same BVH traversal as the ray-traced techniques.
// - model 0 (`vao`): the VAO estimator at the primary ray's surface through the single-pass loop
//   (schedules/single.wgsl) over the all-layers source: every sample's camera ray traced over its
//   interval from the near plane (sources/all_layers.wgsl, column_trace.wgsl).
//   `vao-mean` runs model 0 once per turn of the 4×4 pattern and sums a sixteenth of each.
// - model 1 (`hemisphere`): cosine-weighted rays within R from the surface (common/hemisphere.wgsl,
//   the rays the `hemisphere` estimator traces too), a batch of `spp_count` rays of `spp_total`
//   per dispatch, occlusion summed into `reference_out` across batches.
// Needs common/hash.wgsl, common/hemisphere.wgsl and common/vertex_normal.wgsl in front. Its own parameters and output take the schedule group.

struct ReferenceParams {
    model: u32,
    spp_start: u32,
    spp_count: u32,
    spp_total: u32,
    falloff: u32,
    seed: u32,
    // Model 0: the share of this dispatch in the pixel's AO (1; 1/16 for `vao-mean`, one
    // dispatch per turn of the pattern, View pattern_offset).
    weight: f32,
    _pad1: u32,
}

@group(GROUP_SCHEDULE) @binding(REFERENCE_PARAMS) var<uniform> reference: ReferenceParams;
// Per visible pixel: the AO (vao model) or the summed occlusion of the rays so far (hemisphere).
@group(GROUP_SCHEDULE) @binding(REFERENCE_OUT) var<storage, read_write> reference_out: array<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) global_id: vec3<u32>) {
    let id = global_id.xy;
    if (any(id >= view.visible_size)) {
        return;
    }
    let index = id.y * view.visible_size.x + id.x;
    let pixel = id + vec2<u32>(view.guard_band);
    let dir_view = pixel_to_view(view, vec2<f32>(pixel) + 0.5, 1.0);
    let origin = ray_camera.camera_to_world[3].xyz;
    let dir = (ray_camera.camera_to_world * vec4<f32>(dir_view, 0.0)).xyz;
    let hit = bvh_closest_hit(origin, dir, ray_camera.near, 3.4e38);
    if (hit.t < 0.0) {
        reference_out[index] = select(0.0, 1.0, reference.model == 0u);
        return;
    }
    let tri = bvh_triangles[hit.slot];
    let p0 = bvh_positions[tri.x].xyz;
    var n = cross(bvh_positions[tri.y].xyz - p0, bvh_positions[tri.z].xyz - p0);
    n = select(vec3<f32>(0.0), normalize(n), length(n) > 0.0);
    if (dot(n, dir) > 0.0) {
        n = -n;
    }
    // Shading normals where the scene uses them (the attributes hold none otherwise): the rule of
    // Scene::surface_normal.
    let n0 = decode_vertex_normal(bvh_attributes[tri.x].zw);
    let n1 = decode_vertex_normal(bvh_attributes[tri.y].zw);
    let n2 = decode_vertex_normal(bvh_attributes[tri.z].zw);
    if (length(n) > 0.0 && all(vec3<f32>(dot(n0, n0), dot(n1, n1), dot(n2, n2)) > vec3<f32>(0.0))) {
        n = oriented_shading_normal(n0 * (1.0 - hit.u - hit.v) + n1 * hit.u + n2 * hit.v, n);
    }
    if (reference.model == 0u) {
        let to_view = transpose(mat3x3<f32>(
            ray_camera.camera_to_world[0].xyz,
            ray_camera.camera_to_world[1].xyz,
            ray_camera.camera_to_world[2].xyz,
        ));
        let p = vao_pixel_at(id, dir_view * hit.t, to_view * n);
        reference_out[index] += reference.weight * single_pass_ao(p);
        return;
    }
    // Hemisphere: offset along the normal as the CPU model does.
    let world = origin + dir * hit.t;
    let radius = params.radius;
    let start = world + n * max(1e-4 * radius, 1e-6 * max(max(abs(world.x), abs(world.y)), abs(world.z)));
    let basis = orthonormal_basis(n);
    let rotation = pixel_rotation_2d(reference.seed, id.x, id.y);
    var occlusion = 0.0;
    for (var i = reference.spp_start; i < reference.spp_start + reference.spp_count; i++) {
        let ray_dir = hemisphere_direction(i, reference.spp_total, rotation, n, basis);
        if (reference.falloff != 0u) {
            let occluder = bvh_closest_hit(start, ray_dir, 0.0, radius);
            if (occluder.t >= 0.0) {
                occlusion += max(1.0 - occluder.t / radius, 0.0);
            }
        } else if (bvh_any_hit(start, ray_dir, 0.0, radius)) {
            occlusion += 1.0;
        }
    }
    reference_out[index] += occlusion;
}
