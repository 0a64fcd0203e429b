//! BVH construction: obvhs builds the tree, we flatten it into our GPU node layout.
//!
//! obvhs's PLOC builder clusters bottom-up, merging the pairs whose union has the smallest surface
//! area; reinsertion optimisation then moves subtrees to lower the SAH cost, and an SAH-driven leaf
//! collapse chooses the leaf sizes. Spatial pre-splits are off: they put one triangle into several
//! leaves, which would report it twice in `all_hits`.
//!
//! The flattening is ours rather than obvhs's node array as is, for four reasons: the children of
//! each inner node are allocated together in depth-first order (a ray that keeps going to the
//! nearer child touches memory that is close together), sibling pairs start at even indices (one
//! 64-byte block per pair), the triangles' vertices are copied in leaf order (no index chasing in
//! the inner loop), and every box is recomputed from the vertices it bounds (the traversal's
//! conservativeness then rests on this code alone).

use std::time::Duration;

use glam::{Vec3A, Vec4};
use obvhs::{
    aabb::Aabb,
    bvh2::builder::build_bvh2,
    ploc::{PlocSearchDistance, SortPrecision},
    BvhBuildParams,
};

use super::{triangle::is_valid_triangle, Bvh, BvhNode, NodePair};
use crate::scene::Scene;

/// Build parameters, chosen on the 250k-triangle benchmark scene of the tests (rays per CPU-second,
/// one thread, alternating runs; differences under ~8% were noise on that shared machine):
/// - leaves of at most 2 triangles: 1 was as fast but doubles the nodes; 4 and 8 were ~5–10% slower
///   (smaller leaves also suit a GPU traversal);
/// - reinsertion ratio 0.5: ~10% faster rays than obvhs's 0.2 for ~1 s more build; 1.0 gained
///   little more and cost another 1.5 s.
///
/// The rest is obvhs's `slow_build` preset without spatial pre-splits (see the module doc).
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
/// line up far apart (a polygon fan, duplicated geometry, exponentially spaced parts) and then
/// builds a chain about as deep as the triangle count.
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

/// [`Bvh::build`]: SAH (obvhs), replaced by median splits where its tree is deeper than
/// `max_depth` (`None`: any depth, for tests of the traversal's overflow report).
pub(super) fn build(scene: &Scene, max_depth: Option<usize>) -> Bvh {
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
    let mut tree = Tree::from_obvhs(&build_bvh2(&aabbs, PARAMS, &mut Duration::default()));
    if let Some(limit) = max_depth {
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
