// Stenciled VAO: the indirect dispatch size of the compacted phase 2 (64 flagged pixels per
// workgroup), from phase 1's work counter.

@group(0) @binding(0) var<storage, read> work_count: u32;
@group(0) @binding(1) var<storage, read_write> dispatch: array<u32, 3>;

@compute @workgroup_size(1)
fn main() {
    dispatch[0] = (work_count + 63u) / 64u;
    dispatch[1] = 1u;
    dispatch[2] = 1u;
}
