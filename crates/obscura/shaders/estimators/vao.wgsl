// Volumetric Ambient Occlusion (VAO), seed 000 (Brüll, Kern, Grosch 2022) §3.1–3.5, following the
// authors' 2022 shader (docs/AUTHORS_CODE.md §1.2). Mirrored on the CPU by
// src/reference/cpu_vao.rs (the tests hold the two within 1/255).
//
// Per pixel: a disc of radius R perpendicular to the view ray, N line samples on it (radii
// sqrt(1 - psi^(2/3)), psi = van der Corput N..2N-1, angles 2*pi*i/N plus a 4x4 per-pixel rotation).
// Each sample is a column of half-height h = sqrt(R^2 - |d|^2) along the view axis, clipped
// analytically by the surface's hemisphere. Its depth sample gives the free part of the column
// (sphere_vis) or, above the column, the thickness/halo model of §3.3 (halo_vis).
// AO = saturate(2/N * sum(free_i / 2h_i)) ^ exponent (the paper's hemisphere normalisation), or
// with `normalization == 1u` (our default) the ratio sum(free_i / 2h_i) / sum(clipped_i / 2h_i):
// the same integral in the limit, but exactly 1 for any unoccluded plane, where the paper's
// estimator is 1 only on average over the rotation pattern (so it darkens tilted planes in a
// 4x4 pattern after the saturate).
//
// This file is the VAO estimator: it implements the estimator contract (the `estimator_*` functions
// and types at the end, docs/ARCHITECTURE.md) that the schedules (shaders/schedules/) loop over and
// the sources (shaders/sources/) consult. Where a sample's occluder comes from is the source's
// business. The value of one sample is its free column length; several depths for one sample
// combine by the minimum (the lowest visibility wins).
//
// Pixel snapping: the depth sample is read at the centre of the pixel the sample falls in, which
// lies beside the sample's column. Its height is corrected for that lateral offset along the
// surface's tangent plane, so a planar neighbourhood reads exactly its own plane (no
// self-occlusion from snapping); with no offset the height is the paper's dot(D - P, e).

struct VaoParams {
    radius: f32,
    thickness: f32,
    exponent: f32,
    _pad0: u32, // the sample count is the pipeline constant SAMPLE_COUNT
    // Samples whose clipped column is shorter than this fraction of R contribute nothing.
    min_column_fraction: f32,
    // 0: the paper's 2/N normalisation, 1: normalise by the clipped columns' own length.
    normalization: u32,
    _pad1: u32,
    _pad2: u32,
    // Sample i before the pixel's rotation, in units of R: xy its offset on the disc, z its
    // column's half height sqrt(1 − |xy|²), w the reciprocal of z.
    kernel: array<vec4<f32>, 32>,
    // xy: (cos, sin) of the rotation of pixel (x % 4, y % 4), index x % 4 + 4 * (y % 4).
    rotations: array<vec4<f32>, 16>,
}

@group(GROUP_ESTIMATOR) @binding(ESTIMATOR_PARAMS) var<uniform> params: VaoParams;

// Free length of the column [column_end, column_start] for an occluder at object-space height z
// (positive towards the camera), seed 000 Fig. 4 / Eq. 8: inside the column the part above z is
// free; above the column up to `halo_from` = (1 + thickness) R the column is fully occluded
// (constant area); above that it becomes visible again linearly over one column length (falloff
// area).
// The falloff area's visible part, saturate((z − halo_from) / length) · length, is written as a
// clamp, which is the same for any column that counts (length > 0) and has no division.
fn column_visibility(halo_from: f32, z: f32, column_start: f32, column_end: f32) -> f32 {
    let length = column_start - column_end;
    let sphere_vis = max(column_start - max(column_end, z), 0.0);
    let halo_vis = clamp(z - halo_from, 0.0, length);
    return sphere_vis + halo_vis;
}

// The shading point's sample frame: `axis` points to the camera and the sample disc is
// perpendicular to it. The rest is what every sample of the pixel would otherwise make again
// (an AO pass is bound by its per-sample arithmetic, BENCHMARKS.md): `plane` turns an offset
// from `pos` into its column height (see column_height), `disc_x`/`disc_y` are the disc's axes
// turned by the pixel's rotation and scaled by R (a kernel entry's view-space offset is
// k.x disc_x + k.y disc_y), and `crossing` gives where the tangent plane crosses a kernel entry's
// column (−dot(k.xy, crossing)). Nothing else is kept: what stays live through the sample loop
// costs registers (with bent normals, a frame that also kept the disc's own axes and the normal
// measured 0.1019 ms against 0.0928, H200, BENCHMARKS.md).
struct VaoFrame {
    pos: vec3<f32>,
    axis: vec3<f32>,
    plane: vec3<f32>,
    // The plane vector's dot product with a view ray's point at depth 1, as an affine function
    // of its framebuffer point (estimator_occluder_at), and with `pos`.
    ray_plane: vec3<f32>,
    plane_at_pos: f32,
    disc_x: vec3<f32>,
    disc_y: vec3<f32>,
    crossing: vec2<f32>,
    // Framebuffer pixel of the shading point.
    pixel: vec2<u32>,
    // The sphere radius R this pixel uses where the radius is capped on screen (MAX_RADIUS_PX;
    // common/view.wgsl capped_radius; seed 002 §3.5); read through frame_radius.
    capped_radius: f32,
}

// The sphere radius R of the pixel: `params.radius`, or less where the on-screen cap shrinks
// it. Without a cap the pipeline constant folds this to the uniform, so the radius and what is
// made from it stay uniform values (a per-pixel radius in a register cost the vao pass 4 % on an
// H200, BENCHMARKS.md).
fn frame_radius(f: VaoFrame) -> f32 {
    return select(params.radius, f.capped_radius, MAX_RADIUS_PX > 0.0);
}

// Where the column's constant (fully occluding) area ends: (1 + thickness) R above the disc.
fn halo_start(f: VaoFrame) -> f32 {
    return (1.0 + params.thickness) * frame_radius(f);
}

// One line sample: its kernel entry's offset on the disc (`disc`, before the pixel's rotation, in
// units of R), its clipped column [end, start], the height at which the tangent plane crosses it
// (`crossing`, before clipping to the column) and where it projects (unclamped framebuffer pixel
// coordinates).
struct VaoColumn {
    disc: vec2<f32>,
    start: f32,
    end: f32,
    crossing: f32,
    px: vec2<f32>,
}

// Height of view-space point `p` in the column's frame: along the view axis, corrected along the
// tangent plane for its lateral offset from the column (see "Pixel snapping" above). With
// o = p − pos and n the normal in the sample frame (n_xy, n_z), that height is
//   dot(o, axis) + (dot(o, tangent) − d.x, dot(o, bitangent) − d.y) · n_xy / n_z
//   = dot(o, axis + (tangent n_x + bitangent n_y) / n_z) − dot(d, n_xy) / n_z,
// i.e. dot(o, plane) plus the tangent plane's crossing of the column: one dot product a sample.
fn column_height(f: VaoFrame, c: VaoColumn, p: vec3<f32>) -> f32 {
    return dot(p - f.pos, f.plane) + c.crossing;
}

// How fast column_height grows along view-space direction `d`: its linear part. Along a camera
// ray the height is column_height at the camera plus this times the depth; taking the slope as
// the difference of two heights instead loses it to rounding wherever the heights are large next
// to it (a scene far from the camera in world units: at 4096 times the built-ins' scale the
// ray-traced AO moved by up to 4e-3; tests/it/scale_invariance.rs).
fn column_height_slope(f: VaoFrame, d: vec3<f32>) -> f32 {
    return dot(d, f.plane);
}

// The sample count is a pipeline constant so the sample loop unrolls and the depth reads of all
// samples can be in flight together (measured: the loop, not memory, bounds this pass).
override SAMPLE_COUNT: u32 = 8u;

// The shading point of visible pixel `id`; `valid` is false for background.
struct VaoPixel {
    frame: VaoFrame,
    n_z_positive: bool,
    valid: bool,
}

fn vao_pixel(id: vec2<u32>) -> VaoPixel {
    let pixel = id + vec2<u32>(view.guard_band);
    // Both loads before the background test, so the normal's does not wait for the depth (1 %
    // off `vao` on an H200; the other estimators' frame_point measured no change, BENCHMARKS.md).
    let z = textureLoad(depth_tex, pixel, 0).r;
    let normal = textureLoad(normal_tex, pixel, 0).xyz;
    if (is_background(z)) {
        var p: VaoPixel;
        p.valid = false;
        return p;
    }
    let pos = pixel_to_view(view, vec2<f32>(pixel) + 0.5, z);
    return vao_pixel_at(id, pos, normal);
}

// The shading point of visible pixel `id` at view-space `pos` with normal `normal` (any source:
// the G-buffer above, or a primary ray in the ground truth).
fn vao_pixel_at(id: vec2<u32>, pos: vec3<f32>, normal: vec3<f32>) -> VaoPixel {
    var p: VaoPixel;
    p.valid = true;
    let pixel = id + vec2<u32>(view.guard_band);
    let n = normalize(normal);
    // Sample frame perpendicular to the view ray: `axis` points to the camera.
    let axis = toward_camera(view, pos);
    let basis = orthonormal_basis(axis);
    let n_local = vec3<f32>(dot(n, basis[0]), dot(n, basis[1]), dot(n, axis));
    // Avoid division by zero for normals perpendicular to the view ray (seed: makeNonZero 1e-4).
    let n_z = select(min(n_local.z, -1e-4), max(n_local.z, 1e-4), n_local.z >= 0.0);
    let inv_n_z = 1.0 / n_z;
    p.frame.pos = pos;
    p.frame.axis = axis;
    p.frame.pixel = pixel;
    p.frame.capped_radius = capped_radius(view, params.radius, -pos.z);
    p.n_z_positive = n_local.z >= 0.0;
    let rotation = params.rotations[pattern_index(id)].xy;
    let r = frame_radius(p.frame);
    let plane = axis + (basis[0] * n_local.x + basis[1] * n_local.y) * inv_n_z;
    p.frame.plane = plane;
    // pixel_to_view(px, 1) = ((px.x s.x − 1) t.x, (1 − px.y s.y) t.y, −1), s = ndc_per_pixel,
    // t = tan_half_fov (common/view.wgsl), written out: the coefficients taken as differences of
    // pixel_to_view at three points lost too much (an open plane's AO fell below 1 in
    // tests/it/vao_analytic.rs).
    let per_pixel = view.ndc_per_pixel * view.tan_half_fov;
    p.frame.ray_plane = vec3<f32>(
        per_pixel.x * plane.x,
        -per_pixel.y * plane.y,
        view.tan_half_fov.y * plane.y - view.tan_half_fov.x * plane.x - plane.z,
    );
    p.frame.plane_at_pos = dot(pos, plane);
    // d = rotate_by(k.xy, rotation) r, so the offset tangent d.x + bitangent d.y and the
    // crossing −dot(d, n_xy) / n_z are linear in k.xy with these coefficients.
    p.frame.disc_x = (basis[0] * rotation.x + basis[1] * rotation.y) * r;
    p.frame.disc_y = (basis[1] * rotation.x - basis[0] * rotation.y) * r;
    p.frame.crossing = rotate_by(n_local.xy, vec2<f32>(rotation.x, -rotation.y)) * (r * inv_n_z);
    return p;
}

// Sample `i`'s column; `h` is the half height of the unclipped column (pdf 2h), `inv_2h` its
// weight 1 / 2h, and h = 0 marks a sample whose clipped column is too short to count (seed 000
// §3.2: a_i = 0).
struct VaoSample {
    column: VaoColumn,
    h: f32,
    inv_2h: f32,
}

fn vao_sample(p: VaoPixel, i: u32) -> VaoSample {
    let k = params.kernel[i];
    let f = p.frame;
    let r = frame_radius(f);
    var s: VaoSample;
    s.column.disc = k.xy;
    s.h = k.z * r;
    s.inv_2h = k.w * (0.5 / r);
    // Hemisphere clipping: the tangent plane crosses the column at height z_i.
    s.column.crossing = -dot(k.xy, f.crossing);
    let z_i = clamp(s.column.crossing, -s.h, s.h);
    s.column.start = s.h;
    s.column.end = -s.h;
    if (p.n_z_positive) {
        s.column.end = z_i;
    } else {
        s.column.start = z_i;
    }
    if (s.column.start - s.column.end < params.min_column_fraction * r) {
        s.h = 0.0;
        return s;
    }
    s.column.px = view_to_pixel(view, f.pos + f.disc_x * k.x + f.disc_y * k.y);
    return s;
}

// Final AO from the sums of free and clipped column fractions (normalisation, exponent).
fn vao_finish(sum: f32, clipped_sum: f32) -> f32 {
    var ao = 2.0 * sum / f32(SAMPLE_COUNT);
    if (params.normalization == 1u) {
        ao = select(1.0, sum / clipped_sum, clipped_sum > 0.0);
    }
    return pow(saturate(ao), params.exponent);
}

// ---- The estimator contract (docs/ARCHITECTURE.md) ----

alias EstimatorPixel = VaoPixel;
alias EstimatorSample = VaoSample;
// A sample's value: its free column length.
alias EstimatorValue = f32;

// The partial sums a two-phase schedule carries between its phases (three 32-bit words, stored
// next to the pixel's sample mask).
struct EstimatorAccum {
    // Free column fractions of the samples resolved so far.
    sum: f32,
    // Clipped column fractions of every active sample (the `clipped` normalisation).
    clipped_sum: f32,
    _pad: f32,
}

// How an occluder at one depth affects a sample: its value and whether a deeper surface could
// still lower it ("needs hidden depth?", seed 000 §3.7: "if and only if a sample is considered
// occluded").
struct Occluder {
    value: f32,
    hidden: bool,
}

fn estimator_pixel(id: vec2<u32>) -> VaoPixel {
    return vao_pixel(id);
}

fn estimator_pixel_valid(p: VaoPixel) -> bool {
    return p.valid;
}

fn estimator_shading_pixel(p: VaoPixel) -> vec2<u32> {
    return p.frame.pixel;
}

fn estimator_sample(p: VaoPixel, i: u32) -> VaoSample {
    return vao_sample(p, i);
}

// Samples whose clipped column is too short count nowhere (seed 000 §3.2: a_i = 0).
fn estimator_sample_active(s: VaoSample) -> bool {
    return s.h != 0.0;
}

// Where the sample projects: unclamped framebuffer pixel coordinates.
fn estimator_sample_px(p: VaoPixel, s: VaoSample) -> vec2<f32> {
    return s.column.px;
}

// The value of an unoccluded sample: its whole clipped column is free.
fn estimator_unoccluded(p: VaoPixel, s: VaoSample) -> f32 {
    return s.column.start - s.column.end;
}

// A surface at view-space `pos` as the sample's occluder.
fn estimator_occluder(p: VaoPixel, s: VaoSample, pos: vec3<f32>) -> Occluder {
    return occluder_at_height(p, s, column_height(p.frame, s.column, pos));
}

// The surface at framebuffer point `px` and linear depth `z` as the sample's occluder, what the
// depth-buffer sources read. A perspective view puts that point at z (a(px), −1) with a affine
// in px (common/view.wgsl's pixel_to_view), so its column height dot(point − pos, plane) +
// crossing is z (ray_plane · (px, 1)) − dot(pos, plane) + crossing: two multiply-adds and a
// multiply where the view-space point took seven operations and the height five more.
fn estimator_occluder_at(p: VaoPixel, s: VaoSample, px: vec2<f32>, z: f32) -> Occluder {
    if (ORTHOGRAPHIC) {
        return estimator_occluder(p, s, pixel_to_view(view, px, z));
    }
    let f = p.frame;
    let height = z * (f.ray_plane.x * px.x + f.ray_plane.y * px.y + f.ray_plane.z)
        + (s.column.crossing - f.plane_at_pos);
    return occluder_at_height(p, s, height);
}

// An occluder at column height `height`: only one beyond the constant area can hide a lower
// visibility behind it (in the constant area the visibility is already 0).
fn occluder_at_height(p: VaoPixel, s: VaoSample, height: f32) -> Occluder {
    var o: Occluder;
    o.value = column_visibility(halo_start(p.frame), height, s.column.start, s.column.end);
    o.hidden = o.value > 0.0 && height > halo_start(p.frame);
    return o;
}

// Several depths for one sample: the lowest visibility.
fn estimator_combine(a: f32, b: f32) -> f32 {
    return min(a, b);
}

// Missing-occlusion compensation (seed 001 §4; read.wgsl's SD_COMPENSATION): a stochastic
// sample's occluded part of the column, length − free, counts `factor` times (never below 0 free).
// The linear depths along the camera ray through framebuffer point `px` at which a surface can
// lower the sample's value (for the ray-traced stochastic depth map's ray intervals, seed 002
// §3.2). column_visibility is the whole column (no change) for heights at or below the column's
// end and for heights at or above the halo's end, (1 + thickness) R + the column length, so only
// heights strictly between matter. The height of a point is affine in its position
// (column_height), and a point of the ray is affine in its depth, so the height along the ray is
// h(depth) = h0 + depth · slope (h0 at the camera, slope column_height_slope's); the interval is
// where it lies in (end, halo end), widened by a relative 1e-3 for rounding.
fn estimator_depth_interval(p: VaoPixel, s: VaoSample, px: vec2<f32>) -> vec2<f32> {
    let h0 = column_height(p.frame, s.column, vec3<f32>(0.0));
    let slope = column_height_slope(p.frame, pixel_to_view(view, px, 1.0));
    let low = s.column.end;
    let high = halo_start(p.frame) + (s.column.start - s.column.end);
    if (abs(slope) < 1e-12) {
        return vec2<f32>(0.0, 3.0e38);
    }
    let a = (low - h0) / slope;
    let b = (high - h0) / slope;
    let lo = max(min(a, b), 0.0);
    let hi = max(a, b);
    let slack = 1e-3 * hi + 1e-3 * frame_radius(p.frame);
    return vec2<f32>(max(lo - slack, 0.0), hi + slack);
}

fn estimator_compensate(p: VaoPixel, s: VaoSample, value: f32, factor: f32) -> f32 {
    let length = s.column.start - s.column.end;
    return max(length - factor * (length - value), 0.0);
}

fn estimator_accum_init() -> EstimatorAccum {
    return EstimatorAccum(0.0, 0.0, 0.0);
}

// Counts an active sample into the normalisation (whatever its value).
fn estimator_accum_sample(acc: EstimatorAccum, s: VaoSample) -> EstimatorAccum {
    var a = acc;
    a.clipped_sum += (s.column.start - s.column.end) * s.inv_2h;
    return a;
}

// Adds a resolved sample's value.
fn estimator_accum_value(acc: EstimatorAccum, s: VaoSample, value: f32) -> EstimatorAccum {
    var a = acc;
    a.sum += value * s.inv_2h;
    return a;
}

fn estimator_finish(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    return vao_finish(acc.sum, acc.clipped_sum);
}

// No debug image for VAO (Estimator::debug_image): its two-phase and stochastic-depth rows show
// their flagged samples and maps instead.
fn estimator_debug(p: EstimatorPixel, acc: EstimatorAccum) -> f32 {
    return 0.0;
}

// Bent normals (`bent_normals`, seed 001 §4; ours for VAO): the direction from the shading point
// to the centroid of the free volume. A sample's free part of its column is taken as its top
// `value` (exact inside the column, where the free part runs from the occluder up to the column's
// top; a convention for the thickness model's partly visible columns above it), so its centroid
// lies at height start − value/2 over the disc point d; weighted by the free length over the
// column's pdf 2h, as the AO sums it. The schedule sums these over the samples' values and over
// their unoccluded values (the open hemisphere's free volume).
// The vector's lateral part is the kernel entry's unturned offset in units of R (the offset d is
// that entry turned by the pixel's rotation and scaled by R), its height along the axis: the sums
// are linear, so estimator_bent_normal turns them into view space once per pixel (through
// disc_x, disc_y and axis) rather than every sample.
fn estimator_bent_sample(p: VaoPixel, s: VaoSample, value: f32) -> vec3<f32> {
    // The same weight 1 / 2h as estimator_accum_value's.
    return vec3<f32>(s.column.disc, s.column.start - 0.5 * value) * (value * s.inv_2h);
}

// The bent normal from the summed free centroids against the open ones (common/bent.wgsl), view
// space; the normal is rebuilt from the sample frame.
fn estimator_bent_normal(
    p: VaoPixel,
    acc: EstimatorAccum,
    sample_visible: vec3<f32>,
    sample_open: vec3<f32>,
) -> vec3<f32> {
    let f = p.frame;
    // `plane` is the normal over its component along the axis (see column_height; up to the
    // clamp of that component away from 0).
    let normal = normalize(f.plane) * select(-1.0, 1.0, p.n_z_positive);
    let sums_to_view = mat3x3<f32>(f.disc_x, f.disc_y, f.axis);
    return bent_from_sums(normal, sums_to_view * sample_visible, sums_to_view * sample_open);
}
