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
// (shaders/raster/occlusion_pyramid.wgsl) are nearer than the triangle at every pixel it may cover
// (hidden_by_pyramid). Every triangle that can win a pixel is still drawn, by one phase or the
// other.

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
// Tiles per side a triangle's bounds are tested against (hidden_by_pyramid): at most 8 × 8
// pyramid reads. Finer tiles cull more of the hidden triangles that the first phase's
// silhouettes cross, but each read waits for the last: on Crytek Sponza at 1080p with a still
// camera the second phase drew 30,478 triangles with 2 × 2 tiles of 4 to 64 pixels and the
// nearest corner alone, 11,903 with 4 × 4 tiles from 1 pixel, the plane and the edges, 8,110
// with 8 × 8 and 6,586 with 16 × 16, and 8 × 8 was the fastest G-buffer (BENCHMARKS.md).
const HIDDEN_TILES: u32 = 8u;
// Tiles per side of the first, coarse test (coarse_tiles_hide).
const COARSE_TILES: u32 = 2u;

// The workgroup's kept triangles as bits, one word per 32 invocations: the first KEPT_WORDS words
// the list this dispatch writes, the next KEPT_WORDS the first phase's list without occlusion
// culling. Each invocation's place in a list is the count of set bits before its own: one barrier
// after the bits are set, where a prefix sum over the workgroup (Hillis and Steele) took sixteen.
const KEPT_WORDS: u32 = GROUP_SIZE / 32u;
var<workgroup> kept_bits: array<atomic<u32>, 2u * KEPT_WORDS>;

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
// bounds of that extent, its corners in pixels and their reversed-Z depths.
struct Coverage {
    may_cover: bool,
    on_screen: bool,
    lo: vec2<f32>,
    hi: vec2<f32>,
    pa: vec2<f32>,
    pb: vec2<f32>,
    pc: vec2<f32>,
    depths: vec3<f32>,
}

fn coverage(tri: vec4<u32>, culls_back: bool) -> Coverage {
    var out: Coverage;
    out.may_cover = false;
    out.on_screen = false;
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
    out.pa = pa;
    out.pb = pb;
    out.pc = pc;
    out.depths = vec3<f32>(a.z / a.w, b.z / b.w, c.z / c.w);
    return out;
}

// Whether a pixel showed triangle `t` last frame (frame numbers start at 1 and `seen_frame` at 0,
// so on the first frame every triangle counts as seen: the first phase draws them all).
fn seen_last_frame(t: u32) -> bool {
    return seen_frame[1u + t] + 1u == seen_frame[0];
}

// Whether every point of the rectangle `lo..hi` lies more than 2 MARGIN pixels outside the
// triangle's edge from `v` along `e` (inside: cross(e, p - v) > 0), so that no pixel centre
// there can be inside it: the largest value over the rectangle is at its corner furthest along
// the inward normal (-e.y, e.x).
fn outside_edge(v: vec2<f32>, e: vec2<f32>, lo: vec2<f32>, hi: vec2<f32>) -> bool {
    let d = select(lo, hi, vec2<f32>(-e.y, e.x) > vec2<f32>(0.0)) - v;
    return e.x * d.y - e.y * d.x < -2.0 * MARGIN * length(e);
}

// Whether the at most COARSE_TILES² tiles of the finest pyramid level that span the pixels `p`
// to `q` all lie in front of `nearest` (the triangle's nearest corner's depth, with slack): then
// so does every pixel it may cover. A few reads decide most triangles before hidden_by_pyramid's
// fine tiles, which wait for each other (BENCHMARKS.md, issue 16).
fn coarse_tiles_hide(p: vec2<u32>, q: vec2<u32>, nearest: f32) -> bool {
    let span = spanning_level(p, q, COARSE_TILES);
    if (!span.found) {
        return false;
    }
    let a = p >> vec2<u32>(span.level);
    let b = q >> vec2<u32>(span.level);
    for (var y = a.y; y <= b.y; y++) {
        for (var x = a.x; x <= b.x; x++) {
            if (!(nearest < pyramid[span.offset + y * span.row + x])) {
                return false;
            }
        }
    }
    return true;
}

// The finest pyramid level whose at most `tiles`² tiles span the pixels `p` to `q`: where its
// tiles start in `pyramid` and its tiles per row (`found` false when no level does).
struct SpanningLevel {
    found: bool,
    level: u32,
    offset: u32,
    row: u32,
}

fn spanning_level(p: vec2<u32>, q: vec2<u32>, tiles: u32) -> SpanningLevel {
    let size = vec2<u32>(params.size);
    var out = SpanningLevel(false, 0u, 0u, 0u);
    for (var level = PYRAMID_FIRST_LEVEL; level <= PYRAMID_LAST_LEVEL; level++) {
        let row = pyramid_level_size(size, level);
        if (all((q >> vec2<u32>(level)) - (p >> vec2<u32>(level)) <= vec2<u32>(tiles - 1u))) {
            out = SpanningLevel(true, level, out.offset, row.x);
            break;
        }
        out.offset += row.x * row.y;
    }
    return out;
}

// Whether the first phase's depths are nearer than the triangle's at every pixel centre within
// MARGIN of its pixel bounds that it may cover: unless coarse_tiles_hide decides it, of the
// finest pyramid level whose at most HIDDEN_TILES² tiles cover those pixels (level 0: each
// pixel's own depth), every tile not wholly outside one of the triangle's edges is tested
// against the triangle's nearest depth over the tile's pixel centres: its plane (depth is affine
// in screen space) at the nearest of them, never nearer than its nearest corner. Bounds that no
// level covers with so few tiles decide nothing (false).
fn hidden_by_pyramid(cover: Coverage) -> bool {
    // Only pixels of the framebuffer can show the triangle.
    let first = max(ceil(cover.lo - MARGIN - 0.5), vec2<f32>(0.0));
    let last = min(floor(cover.hi + MARGIN - 0.5), params.size - 1.0);
    if (any(first > last)) {
        return true;
    }
    let d = cover.depths;
    let nearest = max(d.x, max(d.y, d.z));
    let p = vec2<u32>(first);
    let q = vec2<u32>(last);
    if (coarse_tiles_hide(p, q, nearest * (1.0 + DEPTH_SLACK))) {
        return true;
    }
    let e1 = cover.pb - cover.pa;
    let e2 = cover.pc - cover.pa;
    let det = e1.x * e2.y - e1.y * e2.x;
    let edges = dot(e1, e1) + dot(e2, e2);
    // The winding is sure well above det's rounding (about 1e-7 of `edges`): then the edges
    // a→b→c below run counter-clockwise (cross(e, inside) > 0).
    let edges_known = abs(det) >= 1.0e-4 * edges;
    let pb = select(cover.pc, cover.pb, det > 0.0);
    let pc = select(cover.pb, cover.pc, det > 0.0);
    // The plane's gradient where the triangle is no sliver (twice its area at least a twentieth
    // of its edges' squared lengths: the solve is well conditioned), else 0 and the plane's depth
    // at the first corner `at_pa` the nearest corner's, which bounds the triangle everywhere.
    // Slack: the solve's rounding, and the rasteriser's snapping of the corners (within MARGIN)
    // moving the plane by its gradient.
    var gradient = vec2<f32>(0.0);
    var at_pa = nearest;
    if (abs(det) >= 0.05 * edges) {
        let d1 = d.y - d.x;
        let d2 = d.z - d.x;
        gradient = vec2<f32>(d1 * e2.y - d2 * e1.y, d2 * e1.x - d1 * e2.x) / det;
        at_pa = d.x;
    }
    let slack = 1.0e-4 * (nearest - min(d.x, min(d.y, d.z)))
        + 2.0 * MARGIN * (abs(gradient.x) + abs(gradient.y));
    let span = spanning_level(p, q, HIDDEN_TILES);
    if (!span.found) {
        return false;
    }
    let level = span.level;
    let a = p >> vec2<u32>(level);
    let b = q >> vec2<u32>(level);
    for (var y = a.y; y <= b.y; y++) {
        for (var x = a.x; x <= b.x; x++) {
            let tile = vec2<u32>(x, y);
            // The tile's pixel centres within the bounds.
            let lo = max(vec2<f32>(tile << vec2<u32>(level)), first) + 0.5;
            let hi = min(vec2<f32>(((tile + 1u) << vec2<u32>(level)) - 1u), last) + 0.5;
            if (edges_known && (outside_edge(cover.pa, pb - cover.pa, lo, hi)
                || outside_edge(pb, pc - pb, lo, hi)
                || outside_edge(pc, cover.pa - pc, lo, hi))) {
                continue;
            }
            let at = select(lo, hi, gradient > vec2<f32>(0.0));
            let plane = at_pa + dot(gradient, at - cover.pa) + slack;
            let depth = min(plane, nearest) * (1.0 + DEPTH_SLACK);
            if (!(depth < pyramid[span.offset + y * span.row + x])) {
                return false;
            }
        }
    }
    return true;
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
    // Workgroup memory starts unset (src/gpu: no zero-initialisation); the barrier after the
    // coverage tests orders these stores before the bits are set.
    if (i < 2u * KEPT_WORDS) {
        atomicStore(&kept_bits[i], 0u);
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
                    && hidden_by_pyramid(cover);
                keep = select(0u, wanted, cover.may_cover && !hidden);
            }
        }
    }
    // The kept triangles stay in their order, so depth ties resolve as they did without
    // culling: each one's place is the number kept up to it (inclusive), both lists at once
    // (`before`: this dispatch's list in the low half, the full list in the high half).
    workgroupBarrier();
    let word = i >> 5u;
    let bit = 1u << (i & 31u);
    if ((keep & 1u) != 0u) {
        atomicOr(&kept_bits[word], bit);
    }
    if ((keep & 0x10000u) != 0u) {
        atomicOr(&kept_bits[KEPT_WORDS + word], bit);
    }
    workgroupBarrier();
    // The bits of this word up to this invocation's (bit << 1 wraps to 0 for the last: all).
    let up_to = (bit << 1u) - 1u;
    var kept = countOneBits(atomicLoad(&kept_bits[word]) & up_to);
    var kept_full = countOneBits(atomicLoad(&kept_bits[KEPT_WORDS + word]) & up_to);
    for (var w = 0u; w < word; w++) {
        kept += countOneBits(atomicLoad(&kept_bits[w]));
        kept_full += countOneBits(atomicLoad(&kept_bits[KEPT_WORDS + w]));
    }
    let before = kept | (kept_full << 16u);
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
