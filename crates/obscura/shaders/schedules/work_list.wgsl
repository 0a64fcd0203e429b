// The two-phase schedule's work list (seed 000 §3.8, §3.9; src/schedules/two_phase.rs): phase 1
// appends the pixels it left flagged, the indirect pass sizes phase 2's dispatch from their
// count, phase 2 works through them. The count heads the list's buffer rather than having a
// buffer of its own, so that phase 2 of the ray-traced rows binds at most WebGPU's default of 8
// storage buffers per stage. The indices start 128 bytes in (WORK_ITEMS_OFFSET in
// two_phase.rs), so that a warp's 32 consecutive indices are one 128-byte line as before.

// Phase 1's view: the count is its atomic append cursor.
struct WorkList {
    count: atomic<u32>,
    @align(128) items: array<u32>,
}

// Phase 2's and the indirect pass's view of the same bytes.
struct WorkListRead {
    count: u32,
    @align(128) items: array<u32>,
}
