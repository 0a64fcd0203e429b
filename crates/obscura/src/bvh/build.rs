//! BVH construction: our PLOC clusters the triangles, obvhs optimises the tree, we flatten it into
//! our GPU node layout.
//!
//! PLOC (Meister and Bittner 2018) clusters bottom-up, merging the pairs whose union has the
//! smallest surface area; obvhs's reinsertion optimisation then moves subtrees to lower the SAH
//! cost, and its SAH-driven leaf collapse chooses the leaf sizes. Spatial pre-splits are off: they
//! put one triangle into several leaves, which would report it twice in `all_hits`.
//!
//! The clustering is ours rather than obvhs's because obvhs's stalls on some inputs (issue 62,
//! defect 1): where many boxes tie (duplicated triangles) or nest (a polygon fan, whose boxes all
//! hold the shared vertex), every cluster picks the last of its equally good neighbours, few picks
//! are mutual, an iteration merges a handful of pairs, and the build takes time quadratic in the
//! triangle count (20,000 copies of one triangle: 25 s). `ploc` breaks ties towards the nearer
//! neighbour and the aligned pair, and when an iteration still merges too few it pairs neighbours in
//! Morton order, so the cluster count falls geometrically: O(n log n) for any input. Reinsertion
//! also grows faster than n log n on such inputs (its searches cannot prune among overlapping
//! boxes) and is skipped where the clustering had to force pairs.
//!
//! The flattening is ours rather than obvhs's node array as is, for four reasons: the children of
//! each inner node are allocated together in depth-first order (a ray that keeps going to the
//! nearer child touches memory that is close together), sibling pairs start at even indices (one
//! 64-byte block per pair), the triangles' vertices are copied in leaf order (no index chasing in
//! the inner loop), and every box is recomputed from the vertices it bounds (the traversal's
//! conservativeness then rests on this code alone).

use glam::{Vec3A, Vec4};
use obvhs::{
    aabb::Aabb,
    bvh2::{
        builder::build_bvh2, leaf_collapser::collapse, node::Bvh2Node,
        reinsertion::ReinsertionOptimizer, Bvh2,
    },
    ploc::{PlocSearchDistance, SortPrecision},
    BvhBuildParams,
};
use rayon::prelude::*;

use super::{triangle::is_valid_triangle, Bvh, BvhNode, NodePair};
use crate::scene::Scene;

/// Build parameters, chosen on the 250k-triangle benchmark scene of the tests (rays per CPU-second,
/// one thread, alternating runs; differences under ~8% were noise on that shared machine):
/// - leaves of at most 2 triangles: 1 was as fast but doubles the nodes; 4 and 8 were ~5–10% slower
///   (smaller leaves also suit a GPU traversal);
/// - reinsertion ratio 0.5: ~10% faster rays than obvhs's 0.2 for ~1 s more build; 1.0 gained
///   little more and cost another 1.5 s.
///
/// The rest is obvhs's `slow_build` preset without spatial pre-splits (see the module doc). Our
/// clustering (`ploc`) reads the reinsertion and collapse fields and searches [`PLOC_WINDOW`]
/// neighbours (obvhs's `High`); obvhs's whole build reads them all where a test asks for its tree
/// ([`Shape::Obvhs`]).
const PARAMS: BvhBuildParams = BvhBuildParams {
    pre_split: false,
    ploc_search_distance: PlocSearchDistance::High,
    search_depth_threshold: 2,
    reinsertion_batch_ratio: 0.5,
    post_collapse_reinsertion_batch_ratio_multiplier: 2.0,
    sort_precision: SortPrecision::U64,
    max_prims_per_leaf: 2,
    collapse_traversal_cost: 3.0,
};

/// PLOC's search window: each cluster looks at this many neighbours on either side in Morton order
/// (`PARAMS.ploc_search_distance`).
const PLOC_WINDOW: usize = 24;

/// Which tree [`build`] makes.
#[derive(Clone, Copy, Debug)]
pub(super) enum Shape {
    /// Ours, replaced by median splits where it is deeper than this.
    Bounded(usize),
    /// Ours, however deep.
    Unbounded,
    /// obvhs's own build as it comes, however deep: its clustering stalls into chains on
    /// degenerate inputs (see the module doc), which tests of the traversal's overflow report need.
    Obvhs,
}

/// The vertices of scene triangle `i`, or `None` when an index is out of range.
pub(super) fn triangle_vertices(scene: &Scene, i: usize) -> Option<[Vec3A; 3]> {
    let tri = scene.triangles.get(i)?;
    let p = |k: usize| {
        scene
            .positions
            .get(tri[k] as usize)
            .map(|&v| Vec3A::from(v))
    };
    Some([p(0)?, p(1)?, p(2)?])
}

/// Deepest tree [`crate::bvh::Bvh::build`] keeps from the SAH builder by default: inside the GPU
/// traversal's 64-entry stack (`gpu::STACK_SIZE`) when the tree is walked two-wide, as it is where
/// its four-wide walk could need more. SAH cannot separate triangles whose centroids coincide or
/// line up far apart (a polygon fan, duplicated geometry, exponentially spaced parts); `ploc`
/// then pairs them by force, O(log n) levels but not always within this bound (each iteration
/// adds a level, and reinsertion may deepen the tree), and median splits take over.
pub const MAX_DEPTH: usize = 48;

/// The tree a builder made, before flattening: inner nodes' children at `first` and `first + 1`,
/// leaves' primitives at `primitive_indices[first .. first + count]` (positions in the box list).
struct Tree {
    /// (is leaf, first, count).
    nodes: Vec<(bool, u32, u32)>,
    primitive_indices: Vec<u32>,
}

impl Tree {
    fn from_obvhs(tree: &obvhs::bvh2::Bvh2) -> Self {
        Self {
            nodes: tree
                .nodes
                .iter()
                .map(|n| (n.is_leaf(), n.first_index, n.prim_count))
                .collect(),
            primitive_indices: tree.primitive_indices.clone(),
        }
    }

    fn depth(&self) -> usize {
        let mut deepest = 0;
        let mut stack = vec![(0usize, 0usize)];
        while let Some((i, depth)) = stack.pop() {
            deepest = deepest.max(depth);
            let (leaf, first, _) = self.nodes[i];
            if !leaf {
                stack.extend([(first as usize, depth + 1), (first as usize + 1, depth + 1)]);
            }
        }
        deepest
    }

    /// Median splits: the primitives sorted along the longest axis of their centroids' box and
    /// halved (by count where the centroids coincide), leaves of at most 2. Depth ⌈log₂(n/2)⌉ for
    /// any input; written here because it is the fallback for the inputs SAH fails on, where
    /// balance matters and quality does not.
    fn median(aabbs: &[Aabb]) -> Self {
        let centre = |i: u32| {
            let b = &aabbs[i as usize];
            (b.min + b.max) * 0.5
        };
        let mut order: Vec<u32> = (0..aabbs.len() as u32).collect();
        let mut nodes = vec![(true, 0, 0)];
        // (node, range of `order`)
        let mut stack = vec![(0usize, 0usize, order.len())];
        while let Some((node, lo, hi)) = stack.pop() {
            if hi - lo <= 2 {
                nodes[node] = (true, lo as u32, (hi - lo) as u32);
                continue;
            }
            let (cmin, cmax) = order[lo..hi]
                .iter()
                .fold((Vec3A::INFINITY, Vec3A::NEG_INFINITY), |(a, b), &i| {
                    (a.min(centre(i)), b.max(centre(i)))
                });
            let extent = cmax - cmin;
            let axis = if extent.x >= extent.y && extent.x >= extent.z {
                0
            } else if extent.y >= extent.z {
                1
            } else {
                2
            };
            let mid = lo + (hi - lo) / 2;
            if extent[axis] > 0.0 {
                order[lo..hi].select_nth_unstable_by(mid - lo, |&a, &b| {
                    centre(a)[axis].total_cmp(&centre(b)[axis])
                });
            }
            let children = nodes.len();
            nodes.extend([(true, 0, 0); 2]);
            nodes[node] = (false, children as u32, 0);
            stack.push((children + 1, mid, hi));
            stack.push((children, lo, mid));
        }
        Self {
            nodes,
            primitive_indices: order,
        }
    }
}

/// The bits of `v` (21 used) spread three apart: one axis of a 63-bit Morton code.
fn spread_bits(v: u32) -> u64 {
    let mut x = u64::from(v) & 0x1f_ffff;
    x = (x | x << 32) & 0x001f_0000_0000_ffff;
    x = (x | x << 16) & 0x001f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}

/// PLOC over `aabbs` (not empty): an obvhs tree of one primitive a leaf (leaf `first_index` =
/// position in `aabbs`, children after their parents), and whether some iteration had to force
/// pairs (the input is degenerate: see the module doc).
///
/// Each iteration every cluster picks the neighbour within [`PLOC_WINDOW`] (Morton order; the
/// next neighbours only in the first iterations) whose union with it has the least surface area;
/// mutual picks merge. Ties, which coincident and nested
/// boxes make common, go to the nearer neighbour and then to the aligned pair (2k, 2k + 1): with
/// obvhs's rule (the last of the tied) picks are rarely mutual. An iteration that merges fewer than
/// 1/16 of the clusters also merges each run of unmerged neighbours pairwise, so every iteration
/// removes at least 1/32 of the clusters: O(log n) iterations of O(n) work each.
fn ploc(aabbs: &[Aabb]) -> (Bvh2, bool) {
    let n = aabbs.len();
    let (lo, hi) = aabbs
        .iter()
        .fold((Vec3A::INFINITY, Vec3A::NEG_INFINITY), |(lo, hi), b| {
            (lo.min(b.center()), hi.max(b.center()))
        });
    const GRID: f32 = ((1u32 << 21) - 1) as f32;
    let scale = GRID / (hi - lo).max(Vec3A::splat(f32::MIN_POSITIVE));
    // (code, index): the index breaks ties, so the order (and the tree) does not depend on the
    // sort's threads.
    let mut keyed: Vec<(u64, u32)> = aabbs
        .par_iter()
        .enumerate()
        .map(|(i, b)| {
            let q = ((b.center() - lo) * scale).clamp(Vec3A::ZERO, Vec3A::splat(GRID));
            let code = spread_bits(q.x as u32)
                | spread_bits(q.y as u32) << 1
                | spread_bits(q.z as u32) << 2;
            (code, i as u32)
        })
        .collect();
    keyed.par_sort_unstable();

    let mut bvh = Bvh2 {
        nodes: vec![Bvh2Node::default(); 2 * n - 1],
        primitive_indices: (0..n as u32).collect(),
        ..Bvh2::default()
    };
    let mut current: Vec<Bvh2Node> = keyed
        .iter()
        .map(|&(_, i)| Bvh2Node::new(aabbs[i as usize], 1, i))
        .collect();
    let mut next = Vec::with_capacity(n);
    let mut best = vec![0u32; n];
    // Pairs are written from the back, so children always come after their parent.
    let mut insert = 2 * n - 1;
    let mut forced = false;
    let mut iteration = 0;
    while current.len() > 1 {
        let count = current.len();
        // The first iterations, over the most clusters, look at the next neighbours only, as
        // obvhs's do (its `search_depth_threshold`): most clusters there pair with one anyway.
        let reach = if iteration < PARAMS.search_depth_threshold {
            1
        } else {
            PLOC_WINDOW
        };
        iteration += 1;
        best[..count]
            .par_iter_mut()
            .enumerate()
            .for_each(|(i, out)| {
                let a = current[i].aabb();
                let mut pick = (f32::INFINITY, usize::MAX, true, i);
                let lo = i.saturating_sub(reach);
                let window = &current[lo..(i + reach + 1).min(count)];
                for (j, other) in (lo..).zip(window) {
                    if j != i {
                        let area = a.union(other.aabb()).half_area();
                        let key = (area, i.abs_diff(j), j != (i ^ 1), j);
                        if (key.0, key.1, key.2) < (pick.0, pick.1, pick.2) {
                            pick = key;
                        }
                    }
                }
                *out = pick.3 as u32;
            });
        let mutual = |i: usize| best[best[i] as usize] as usize == i;
        let stalled = (0..count).filter(|&i| mutual(i)).count() * 16 < count;
        // A few clusters left over at the end are no sign of a degenerate input.
        forced |= stalled && count > 64;
        next.clear();
        let mut i = 0;
        while i < count {
            let (left, right) = if mutual(i) {
                let j = best[i] as usize;
                if j > i {
                    // Merged when its partner comes.
                    i += 1;
                    continue;
                }
                (j, i)
            } else if stalled && i + 1 < count && !mutual(i + 1) {
                i += 1;
                (i - 1, i)
            } else {
                next.push(current[i]);
                i += 1;
                continue;
            };
            insert -= 2;
            bvh.nodes[insert] = current[left];
            bvh.nodes[insert + 1] = current[right];
            let union = current[left].aabb().union(current[right].aabb());
            next.push(Bvh2Node::new(union, 0, insert as u32));
            i += 1;
        }
        std::mem::swap(&mut current, &mut next);
    }
    debug_assert_eq!(insert, 1);
    bvh.nodes[0] = current[0];
    bvh.children_are_ordered_after_parents = true;
    (bvh, forced)
}

/// The tree of `aabbs` (not empty): [`ploc`], reinsertion where the input allows it, leaf
/// collapse.
fn sah_tree(aabbs: &[Aabb]) -> Bvh2 {
    let (mut tree, degenerate) = ploc(aabbs);
    let mut reinsertion = ReinsertionOptimizer::default();
    if degenerate {
        log::debug!("bvh: degenerate input (coincident or nested boxes): no reinsertion");
    } else {
        reinsertion.run(&mut tree, PARAMS.reinsertion_batch_ratio, None);
    }
    collapse(
        &mut tree,
        PARAMS.max_prims_per_leaf,
        PARAMS.collapse_traversal_cost,
    );
    if !degenerate {
        let ratio = PARAMS.reinsertion_batch_ratio
            * PARAMS.post_collapse_reinsertion_batch_ratio_multiplier;
        reinsertion.run(&mut tree, ratio, None);
    }
    tree
}

/// [`Bvh::build`] and its test variants: the tree `shape` asks for.
pub(super) fn build(scene: &Scene, shape: Shape) -> Bvh {
    let start = build_clock();

    // Only triangles that can be hit go into the BVH.
    let mut ids = Vec::with_capacity(scene.triangles.len());
    let mut aabbs = Vec::with_capacity(scene.triangles.len());
    for i in 0..scene.triangles.len() {
        if let Some(p) = triangle_vertices(scene, i).filter(is_valid_triangle) {
            ids.push(i as u32);
            aabbs.push(Aabb::new(
                p[0].min(p[1]).min(p[2]),
                p[0].max(p[1]).max(p[2]),
            ));
        }
    }
    let skipped = scene.triangles.len() - ids.len();
    if skipped > 0 {
        log::debug!(
            "bvh: {skipped} of {} triangles are degenerate or invalid and never hit",
            scene.triangles.len()
        );
    }

    let mut bvh = Bvh {
        scene_triangle_count: scene.triangles.len(),
        ..Bvh::default()
    };
    if ids.is_empty() {
        return bvh;
    }

    // obvhs's leaves refer to positions in `aabbs` (we pass identity indices), so leaf slot →
    // `ids[primitive_indices[slot]]` → scene triangle.
    let mut tree = Tree::from_obvhs(&match shape {
        Shape::Obvhs => build_bvh2(&aabbs, PARAMS, &mut std::time::Duration::default()),
        Shape::Bounded(_) | Shape::Unbounded => sah_tree(&aabbs),
    });
    if let Shape::Bounded(limit) = shape {
        let depth = tree.depth();
        if depth > limit {
            log::warn!(
                "BVH: the SAH tree is {depth} levels deep (over {limit}: triangles SAH cannot \
                 separate, e.g. a polygon fan or duplicated geometry); rebuilt with median splits"
            );
            tree = Tree::median(&aabbs);
        }
    }

    // Depth-first flattening: (source node, destination slot, depth).
    // Root, then a pad so that every sibling pair starts at an even index (see `NodePair`). The pad
    // is an empty box, so even a traversal that reached it by mistake would find nothing there.
    const PAD: BvhNode = BvhNode {
        min: [f32::MAX; 3],
        first: 0,
        max: [f32::MIN; 3],
        count: 0,
    };
    let mut nodes = vec![BvhNode::default(), PAD];
    let mut stack = vec![(0usize, 0usize, 0usize)];
    while let Some((src, dst, depth)) = stack.pop() {
        let (leaf, first_index, prim_count) = tree.nodes[src];
        bvh.max_depth = bvh.max_depth.max(depth);
        if leaf {
            let first = bvh.primitive_indices.len();
            for slot in first_index..first_index + prim_count {
                let id = ids[tree.primitive_indices[slot as usize] as usize];
                let p = triangle_vertices(scene, id as usize).expect("validated above");
                bvh.primitive_indices.push(id);
                bvh.leaf_vertices.push(p);
            }
            nodes[dst] = BvhNode {
                first: first as u32,
                count: prim_count,
                ..BvhNode::default()
            };
        } else {
            let children = nodes.len();
            nodes.extend([BvhNode::default(); 2]);
            nodes[dst] = BvhNode {
                first: children as u32,
                count: 0,
                ..BvhNode::default()
            };
            // Right pushed first so the left subtree is laid out right after this pair.
            let c = first_index as usize;
            stack.push((c + 1, children + 1, depth + 1));
            stack.push((c, children, depth + 1));
        }
    }

    // Boxes, bottom-up: children always come after their parent in `nodes`.
    for i in (0..nodes.len()).rev().filter(|&i| i != 1) {
        let n = nodes[i];
        let (lo, hi) = if n.is_leaf() {
            let verts = &bvh.leaf_vertices[n.first as usize..(n.first + n.count) as usize];
            verts
                .iter()
                .flatten()
                .fold((Vec3A::INFINITY, Vec3A::NEG_INFINITY), |(lo, hi), &v| {
                    (lo.min(v), hi.max(v))
                })
        } else {
            let (l, r) = (&nodes[n.first as usize], &nodes[n.first as usize + 1]);
            (
                Vec3A::from(l.min).min(Vec3A::from(r.min)),
                Vec3A::from(l.max).max(Vec3A::from(r.max)),
            )
        };
        nodes[i].min = lo.to_array();
        nodes[i].max = hi.to_array();
    }
    debug_assert!(nodes.len() % 2 == 0);
    bvh.pairs = nodes
        .chunks_exact(2)
        .map(|p| {
            let (l, r) = (&p[0], &p[1]);
            let axis = |a: usize| Vec4::new(l.min[a], r.min[a], l.max[a], r.max[a]);
            NodePair {
                x: axis(0),
                y: axis(1),
                z: axis(2),
                link: [l.first, l.count, r.first, r.count],
            }
        })
        .collect();
    bvh.nodes = nodes;

    log::debug!(
        "bvh: {} triangles, {} nodes, depth {}, built in {:.1} ms",
        bvh.primitive_indices.len(),
        bvh.nodes().len(),
        bvh.max_depth,
        start.map_or(f64::NAN, |s| s.elapsed().as_secs_f64() * 1e3)
    );
    bvh
}

/// The clock the build's debug log times it with; none on wasm32 (the WebGPU target), where
/// std has no clock and `Instant::now` panics.
fn build_clock() -> Option<std::time::Instant> {
    (!cfg!(target_arch = "wasm32")).then(std::time::Instant::now)
}
