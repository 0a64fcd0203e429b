// The bindings of the sources that trace rays through the BVH (column rays, BVH rays) and of the
// ground truth: the camera (view space to world space), a counter of rays whose traversal
// overflowed its stack, and the BVH itself (src/sources/column_rays.rs binds them).

struct RayCamera {
    // View space -> world space.
    camera_to_world: mat4x4<f32>,
    // Near plane: rays start there.
    near: f32,
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

@group(GROUP_SOURCE) @binding(SOURCE_RAY_CAMERA) var<uniform> ray_camera: RayCamera;
// Rays whose traversal overflowed its stack: their result may be incomplete, so they are counted
// and reported (AmbientOcclusion::read_stack_overflows), never silently wrong.
@group(GROUP_SOURCE) @binding(SOURCE_STACK_OVERFLOWS) var<storage, read_write> stack_overflows: atomic<u32>;

// The BVH (common/bvh.wgsl) in the source group, from binding SOURCE_BVH.
const BVH_GROUP: u32 = GROUP_SOURCE;
const BVH_BINDING: u32 = SOURCE_BVH;
