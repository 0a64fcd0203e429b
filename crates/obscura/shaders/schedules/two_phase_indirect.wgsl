// Two-phase schedule: the indirect dispatch size of the compacted phase 2 (64 flagged pixels per
// workgroup), from phase 1's work counter; beyond 65535 workgroups (the dispatch limit per
// dimension) rows of 65535 (mirrors `dispatch_rows` in src/schedules/two_phase.rs).

@group(0) @binding(INDIRECT_WORK_LIST) var<storage, read> work: WorkListRead;
@group(0) @binding(INDIRECT_DISPATCH) var<storage, read_write> dispatch: array<u32, 3>;

@compute @workgroup_size(1)
fn main() {
    let groups = (work.count + 63u) / 64u;
    dispatch[0] = min(groups, 65535u);
    dispatch[1] = max((groups + 65534u) / 65535u, 1u);
    dispatch[2] = 1u;
}
