// Triangle culling before the raster passes (src/raster/triangle_cull.rs, issue 16). One
// workgroup per draw (a chunk of at most 256 triangles, src/raster/chunks.rs) keeps the triangles
// that can cover a pixel centre, in their order, and writes the draw's indirect arguments. Why:
// on the H100/H200 the raster passes spend most of their time on triangles before any fragment
// is shaded (BENCHMARKS.md: Sponza's G-buffer pass cost 0.84 of its 1.28 ms with every fragment
// rejected), and this chip runs compute far faster than its few raster units run triangles.
//
// A triangle is dropped only when no pixel centre can be inside it (what the rasteriser would
// find), with margins for the rasteriser's own rounding:
// - all three corners outside one plane of the frustum (the near plane included);
// - back-facing, for the triangles drawn with back faces culled, by more than its area can move
//   when every corner moves by MARGIN pixels;
// - no pixel centre within MARGIN pixels of its screen bounding box.
// A triangle that crosses the eye plane, or reaches far outside the framebuffer (where float
// pixel positions lose precision), is tested against the frustum planes only.
//
// With occlusion culling (the G-buffer's visibility pass), two phases (Haar and Aaltonen,
// "GPU-Driven Rendering Pipelines", SIGGRAPH 2015 Advances course): the first keeps, of those, the
// triangles some pixel showed last frame (`seen_frame`, written by gbuffer_resolve_main.wgsl);
// after they are drawn, the second keeps the others unless the first phase's depths
// (shaders/occlusion_pyramid.wgsl) are nearer than the triangle's nearest corner over every pixel
// it may cover. Every triangle that can win a pixel is still drawn, by one phase or the other.

struct CullParams {
    view: mat4x4<f32>,
    projection: mat4x4<f32>,
    // The framebuffer in pixels (guard band included).
    size: vec2<f32>,
    // Number of draws in `draw_list`.
    draws: u32,
    // Non-zero: keep every triangle (the tests' uncull'd twin, src/raster/triangle_cull.rs).
    keep_all: u32,
    // 0: no occlusion culling; 1: the first phase; 2: the second (also the list it writes).
    phase: u32,
    // The first phase also writes the list without occlusion culling (list 0) when non-zero.
    keep_all_list: u32,
    // Where this dispatch's list starts, in triangles and in draws: list `l` (src/raster/
    // triangle_cull.rs, `CullList`) at `l` times the triangle count and `l` times the draw count.
    list_triangles: u32,
    list_draws: u32,
}

// Parameters in read-only storage, not a uniform: Mesa's lavapipe compiles a
// shader variant for each set of uniform values that decide branches (its uniform inlining), and
// the camera changes them every frame it moves. A uniform here made lavapipe compile this shader
// anew each frame, which tests/soak.rs saw as resident memory growing by about 0.16 MiB a frame.
@group(0) @binding(0) var<storage, read> params: CullParams;
@group(0) @binding(1) var<storage, read> positions: array<vec4<f32>>;
// `(i0, i1, i2, material)` per triangle, the raster passes' (chunk) order.
@group(0) @binding(2) var<storage, read> triangles: array<vec4<u32>>;
// Per draw: first triangle, triangle count, draw group (0: back faces culled), unused.
@group(0) @binding(3) var<storage, read> draw_list: array<vec4<u32>>;
// The kept triangles of each draw, from the draw's first triangle on: what the vertex shaders
// read (`drawn_triangle` in gbuffer.wgsl).
@group(0) @binding(4) var<storage, read_write> drawn: array<u32>;
// Per draw, `draw_indirect`'s arguments: vertex count, instance count, first vertex, first
// instance.
@group(0) @binding(5) var<storage, read_write> args: array<vec4<u32>>;
// Occlusion culling only: the current frame number ([0]) and per triangle t the last frame number
// at which a pixel showed it ([1 + t]; one buffer, so the pass stays within WebGPU's eight
// storage buffers per stage); the first phase's occlusion pyramid.
@group(0) @binding(6) var<storage, read> seen_frame: array<u32>;
@group(0) @binding(7) var<storage, read> pyramid: array<f32>;

// Pixels: four times the rasteriser's 1/256-pixel vertex snapping.
const MARGIN: f32 = 0.015625;
// Screen tests only within this many framebuffers of the frame (float pixels stay finer than
// 1/1024 px there).
const SCREEN_REACH: f32 = 4.0;
const GROUP_SIZE: u32 = 256u;
// Workgroups per row of the dispatch (WebGPU's per-dimension limit).
const ROW: u32 = 65535u;
// Relative slack on a triangle's nearest depth against the pyramid: the rasteriser's depth at a
// pixel centre inside the triangle is a convex combination of the corners' (up to rounding, and
// the vertex shader's products may round differently from ours).
const DEPTH_SLACK: f32 = 1.0e-5;

var<workgroup> kept_before: array<u32, GROUP_SIZE>;

// The same two products as gbuffer.wgsl's `view_to_clip(to_view(p))`.
fn clip_of(vertex: u32) -> vec4<f32> {
    let view_pos = (params.view * vec4<f32>(positions[vertex].xyz, 1.0)).xyz;
    return params.projection * vec4<f32>(view_pos, 1.0);
}

// Pixel coordinates (y down, pixel centres at k + 0.5) of a clip position with w > 0.
fn to_pixels(c: vec4<f32>) -> vec2<f32> {
    let ndc = c.xy / c.w;
    return vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * params.size;
}

fn outside_one_plane(a: vec4<f32>, b: vec4<f32>, c: vec4<f32>) -> bool {
    let right = a.x > a.w && b.x > b.w && c.x > c.w;
    let left = a.x < -a.w && b.x < -b.w && c.x < -c.w;
    let top = a.y > a.w && b.y > b.w && c.y > c.w;
    let bottom = a.y < -a.w && b.y < -b.w && c.y < -c.w;
    // Reversed Z: in front of the near plane is z > w (behind the eye too, where w < 0 < z).
    let near = a.z > a.w && b.z > b.w && c.z > c.w;
    return right || left || top || bottom || near;
}

// Whether a pixel centre k + 0.5 lies in [lo - MARGIN, hi + MARGIN].
fn centre_between(lo: f32, hi: f32) -> bool {
    return ceil(lo - MARGIN - 0.5) <= floor(hi + MARGIN - 0.5);
}

// What the culling found of a triangle: whether it may cover a pixel centre; and, where it has
// tested its screen extent (every corner in front of the eye, near the framebuffer), the pixel
// bounds of that extent and the nearest (largest reversed-Z) depth of its corners.
struct Coverage {
    may_cover: bool,
    on_screen: bool,
    lo: vec2<f32>,
    hi: vec2<f32>,
    nearest: f32,
}

fn coverage(tri: vec4<u32>, culls_back: bool) -> Coverage {
    var out = Coverage(false, false, vec2<f32>(0.0), vec2<f32>(0.0), 0.0);
    let a = clip_of(tri.x);
    let b = clip_of(tri.y);
    let c = clip_of(tri.z);
    if (outside_one_plane(a, b, c)) {
        return out;
    }
    out.may_cover = true;
    if (!(a.w > 0.0 && b.w > 0.0 && c.w > 0.0)) {
        return out;
    }
    let pa = to_pixels(a);
    let pb = to_pixels(b);
    let pc = to_pixels(c);
    let lo = min(pa, min(pb, pc));
    let hi = max(pa, max(pb, pc));
    let reach = SCREEN_REACH * params.size;
    if (any(lo < -reach) || any(hi > params.size + reach)) {
        return out;
    }
    if (!centre_between(lo.x, hi.x) || !centre_between(lo.y, hi.y)) {
        out.may_cover = false;
        return out;
    }
    if (culls_back) {
        // Twice the signed area in pixels (y down): positive is clockwise in normalised device
        // coordinates, the back face of a counter-clockwise front face (wgpu's default).
        let ab = pb - pa;
        let ac = pc - pa;
        let area = ab.x * ac.y - ab.y * ac.x;
        // How far the area can move when each corner moves by MARGIN in x and y.
        let slack = 4.0 * MARGIN * (length(ab) + length(ac) + length(pc - pb)) + 16.0 * MARGIN * MARGIN;
        if (area > slack) {
            out.may_cover = false;
            return out;
        }
    }
    out.on_screen = true;
    out.lo = lo;
    out.hi = hi;
    out.nearest = max(a.z / a.w, max(b.z / b.w, c.z / c.w));
    return out;
}

// Whether a pixel showed triangle `t` last frame (frame numbers start at 1 and `seen_frame` at 0,
// so on the first frame every triangle counts as seen: the first phase draws them all).
fn seen_last_frame(t: u32) -> bool {
    return seen_frame[1u + t] + 1u == seen_frame[0];
}

// Whether the first phase's depths are nearer than `nearest` at every pixel centre within
// MARGIN of the pixel bounds `lo..hi`: the farthest of the at most 2×2 pyramid tiles of the
// finest level that covers those pixels. Bounds that reach outside the framebuffer, or that no
// level covers with 2×2 tiles, decide nothing (false).
fn hidden_by_pyramid(lo: vec2<f32>, hi: vec2<f32>, nearest: f32) -> bool {
    let first = ceil(lo - MARGIN - 0.5);
    let last = floor(hi + MARGIN - 0.5);
    if (any(first < vec2<f32>(0.0)) || any(last > params.size - 1.0)) {
        return false;
    }
    let size = vec2<u32>(params.size);
    let p = vec2<u32>(first);
    let q = vec2<u32>(last);
    for (var level = PYRAMID_FIRST_LEVEL; level <= PYRAMID_LAST_LEVEL; level++) {
        let a = p >> vec2<u32>(level);
        let b = q >> vec2<u32>(level);
        if (all(b - a <= vec2<u32>(1u))) {
            let far = min(
                min(pyramid[pyramid_index(size, level, a)], pyramid[pyramid_index(size, level, vec2<u32>(b.x, a.y))]),
                min(pyramid[pyramid_index(size, level, vec2<u32>(a.x, b.y))], pyramid[pyramid_index(size, level, b)]),
            );
            return nearest * (1.0 + DEPTH_SLACK) < far;
        }
    }
    return false;
}

@compute @workgroup_size(256)
fn main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) i: u32,
) {
    let d = group.x + group.y * ROW;
    // Uniform per workgroup: every invocation returns here or none does (the barriers below).
    if (d >= params.draws) {
        return;
    }
    let draw = draw_list[d];
    let t = draw.x + i;
    // Bit 0: kept by this dispatch; bit 16: kept without occlusion culling (the first phase's
    // second list). One prefix sum counts both (at most 256 each).
    var keep = 0u;
    if (i < draw.y) {
        if (params.keep_all != 0u) {
            // The uncull'd twin: everything in the first (or only) phase.
            keep = select(0u, 0x10001u, params.phase != 2u);
        } else {
            // Which lists the triangle may join before its (costlier) coverage: the second phase
            // has no use for those seen last frame, and the first only wants them unless it
            // also writes the full list.
            let seen = params.phase != 0u && seen_last_frame(t);
            let wanted = select(0u, 1u, params.phase == 0u || (params.phase == 1u) == seen)
                | select(0u, 0x10000u, params.phase == 1u && params.keep_all_list != 0u);
            if (wanted != 0u) {
                let cover = coverage(triangles[t], draw.z == 0u);
                let hidden = params.phase == 2u && cover.on_screen
                    && hidden_by_pyramid(cover.lo, cover.hi, cover.nearest);
                keep = select(0u, wanted, cover.may_cover && !hidden);
            }
        }
    }
    // Inclusive prefix sum of `keep` over the workgroup (Hillis and Steele): the kept triangles
    // stay in their order, so depth ties resolve as they did without culling.
    kept_before[i] = keep;
    workgroupBarrier();
    for (var offset = 1u; offset < GROUP_SIZE; offset <<= 1u) {
        var sum = kept_before[i];
        if (i >= offset) {
            sum += kept_before[i - offset];
        }
        workgroupBarrier();
        kept_before[i] = sum;
        workgroupBarrier();
    }
    let before = kept_before[i];
    if ((keep & 1u) != 0u) {
        drawn[params.list_triangles + draw.x + (before & 0xffffu) - 1u] = t;
    }
    let full_list = params.phase == 1u && params.keep_all_list != 0u;
    if (full_list && (keep & 0x10000u) != 0u) {
        drawn[draw.x + (before >> 16u) - 1u] = t;
    }
    if (i == GROUP_SIZE - 1u) {
        let first = params.list_triangles + draw.x;
        args[params.list_draws + d] = vec4<u32>(3u * (before & 0xffffu), 1u, 3u * first, 0u);
        if (full_list) {
            args[d] = vec4<u32>(3u * (before >> 16u), 1u, 3u * draw.x, 0u);
        }
    }
}
