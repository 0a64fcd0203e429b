//! The four-wide BVH the GPU walks (`shaders/common/bvh.wgsl`), collapsed from the flat BVH2 of
//! [`super::Bvh::nodes`]: the same leaves and boxes, about half of the BVH2's levels gone, so a
//! ray takes about half as many steps: on an H200 the 1/4-resolution stochastic depth map of
//! seed 002 §3.3 took 0.71 ms on Crytek Sponza over the BVH2 and 0.50 over this tree
//! (BENCHMARKS.md). The collapse is the common greedy one: a node takes its BVH2 node's two
//! children, then keeps opening the inner child of largest surface area until it has four.
//!
//! Measured and not kept (BENCHMARKS.md, 2026-12-04): boxes stored in bytes on a per-node grid
//! (64-byte nodes, Ylitie et al. 2017) made that map 4–9 % slower, the decoding costing more
//! than the bytes saved; and the map does not wait on single rays' latency either (each ray split
//! over several invocations cost the sum of the parts, not the longest part). A reading, not
//! measured directly: its rays are bound by their instructions.
//!
//! The CPU traversal (`traverse.rs`) stays on the BVH2; both visit the same leaves with the same
//! boxes, so both report the same hits (the GPU's order differs, which only the any-hit stages
//! that keep a sample of hits see).

use bytemuck::{Pod, Zeroable};

use super::BvhNode;

/// One node of the four-wide BVH (128 bytes), WGSL `BvhNode` in `shaders/common/bvh.wgsl`.
///
/// Slot `k` is a child: its box is `(min_x[k], min_y[k], min_z[k])`–`(max_x[k], …)`; with
/// `count[k] > 0` it is a leaf of the triangle slots `child[k] .. child[k] + count[k]`, with
/// `count[k] == 0` the inner node `child[k]`. Unused slots hold an inverted box (`min > max`),
/// which no ray enters.
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct WideNode {
    /// The children's boxes, per axis: minima x, maxima x, minima y, maxima y, minima z, maxima z.
    pub bounds: [[f32; 4]; 6],
    /// Inner child: its index in the wide node array; leaf: its first triangle slot.
    pub child: [u32; 4],
    /// Leaf: its triangle count; 0 for an inner child or an unused slot.
    pub count: [u32; 4],
}

impl WideNode {
    /// A node of four unused slots (what an empty tree's only node is).
    fn empty() -> Self {
        Self {
            bounds: [
                [1.0; 4], [-1.0; 4], [1.0; 4], [-1.0; 4], [1.0; 4], [-1.0; 4],
            ],
            child: [0; 4],
            count: [0; 4],
        }
    }

    fn set_slot(&mut self, k: usize, box_of: &BvhNode, child: u32, count: u32) {
        for axis in 0..3 {
            self.bounds[2 * axis][k] = box_of.min[axis];
            self.bounds[2 * axis + 1][k] = box_of.max[axis];
        }
        self.child[k] = child;
        self.count[k] = count;
    }
}

/// The wide tree of a flat BVH2 with at most `width` (2 to 4) children a node, root at index 0
/// (one node of unused slots for an empty tree), and a bound on the GPU traversal's stack: the most
/// entries a nearest-child-first walk can hold, the sum over a root-to-leaf path of each node's
/// children (leaves too: they wait on the stack) less the one walked into. At width 2 the tree is
/// the BVH2 itself, whose bound is at most its depth.
pub fn widen(nodes: &[BvhNode], width: usize) -> (Vec<WideNode>, usize) {
    assert!((2..=4).contains(&width), "a wide node has 2 to 4 children");
    let mut wide = vec![WideNode::empty()];
    if nodes.len() < 2 {
        return (wide, 0);
    }
    let area = |n: &BvhNode| {
        let d = [0, 1, 2].map(|a| (n.max[a] - n.min[a]).max(0.0));
        d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
    };
    // (wide node, the BVH2 node whose children it holds); the BVH2 root is itself a leaf in a
    // one-triangle tree.
    let mut todo = vec![(0usize, 0usize)];
    while let Some((w, opened)) = todo.pop() {
        let root = &nodes[opened];
        let mut kids: Vec<usize> = if root.is_leaf() {
            vec![opened]
        } else {
            vec![root.first as usize, root.first as usize + 1]
        };
        while kids.len() < width {
            let Some(open) = (0..kids.len())
                .filter(|&i| !nodes[kids[i]].is_leaf())
                .max_by(|&a, &b| area(&nodes[kids[a]]).total_cmp(&area(&nodes[kids[b]])))
            else {
                break;
            };
            let first = nodes[kids.swap_remove(open)].first as usize;
            kids.extend([first, first + 1]);
        }
        for (k, &kid) in kids.iter().enumerate() {
            let n = nodes[kid];
            if n.is_leaf() {
                wide[w].set_slot(k, &n, n.first, n.count);
            } else {
                let index = wide.len();
                wide.push(WideNode::empty());
                wide[w].set_slot(k, &n, index as u32, 0);
                todo.push((index, kid));
            }
        }
    }
    // Children come after their parents, so one pass from the back has every child's need ready:
    // a node's pushes (its used slots less the one walked into) plus its neediest inner child's.
    let mut need = vec![0usize; wide.len()];
    for w in (0..wide.len()).rev() {
        let n = &wide[w];
        let used = (0..4).filter(|&k| n.bounds[0][k] <= n.bounds[1][k]);
        let pushes = used.clone().count().saturating_sub(1);
        let deepest = used
            .filter(|&k| n.count[k] == 0)
            .map(|k| need[n.child[k] as usize])
            .max()
            .unwrap_or(0);
        need[w] = pushes + deepest;
    }
    (wide, need[0])
}
