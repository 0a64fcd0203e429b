//! CPU bounding volume hierarchy over a [`Scene`]: the ray-tracing oracle that the GPU traversal is
//! held to (docs/ARCHITECTURE.md, "Conventions"), and the flat BVH2 that is uploaded to it.
//!
//! # What is where
//! - `build.rs`: SAH-quality build with obvhs (PLOC + reinsertion + SAH leaf collapse), then our
//!   own flattening into [`BvhNode`]s (sibling pairs adjacent, depth-first order) with the
//!   triangles copied into leaf order so a leaf's vertices are contiguous in memory.
//! - `triangle.rs`: the ray/triangle test — the *watertight* test of Woop, Benthin and Wald
//!   ("Watertight Ray/Triangle Intersection", JCGT 2013), not Möller–Trumbore. Why: this is the
//!   oracle; AO rays start on surfaces and graze edges of closed meshes, and Möller–Trumbore in f32
//!   rounds the two sides of a shared edge differently, so rays can slip through between them. The
//!   watertight test computes the three edge functions from per-vertex values that do not depend on
//!   which triangle a vertex belongs to, so a shared edge yields exactly opposite values on both
//!   sides and no ray leaks. Edges are inclusive: a ray exactly through a shared edge (or vertex)
//!   reports every triangle touching it.
//! - `traverse.rs`: the stack-based, nearest-child-first traversal, over a CPU copy of the nodes in
//!   which each sibling pair is transposed for one 4-wide box test (`NodePair`, one cache line);
//!   the tree and its order are those of [`Bvh::nodes`]. We do not use obvhs's own traversal
//!   because (a) its `Ray::new` debug-asserts finite input (we must return "no hit" for NaN/inf
//!   rays), (b) its ray/box test clamps tiny direction components to ±1/ε, which is not
//!   conservative and can cull boxes the ray does pass through — unacceptable in an oracle — and it
//!   mishandles origins lying exactly on a box face of a zero direction component, and (c) the GPU
//!   traversal walks the same boxes and leaves with the same tests (four-wide, `wide.rs`), so the
//!   CPU version is its reference.
//! - `wide.rs`: the four-wide tree the GPU walks, collapsed from this BVH2.
//! - `framing.rs`: an automatic camera for a scene that names none, placed by probing rays.
//!
//! # Rules a hit must pass (the scene contract, `scene/types.rs`)
//! A candidate triangle hit with parameter `t` in `[t_min, t_max]` (inclusive, in units of
//! `ray.dir`) counts when
//! - it is a front face (counter-clockwise seen from the ray origin, `dot(dir, cross(p1-p0, p2-p0))
//!   < 0`), or the material [keeps back faces](crate::scene::Material::keeps_back_faces), and
//! - the material [passes the alpha test](crate::scene::Material::passes_alpha_test) at the uv
//!   interpolated from `scene.uvs` with the hit's barycentrics.
//!
//! Triangles with zero area (as computed in f32), out-of-range vertex indices or non-finite
//! vertices are left out of the BVH and never hit. A triangle whose material index is out of range
//! is treated as opaque and single-sided. Rays with a non-finite or zero direction, a non-finite
//! origin, or an empty/NaN interval hit nothing. Nothing here panics on scene data.
//!
//! Every query takes the `&Scene` the BVH was built from: vertex positions are copied into the BVH
//! (leaf order), but materials, uvs and textures are read from the scene at hit time.
//!
//! # Layout
//! [`Bvh::nodes`] is a flat array of 32-byte [`BvhNode`]s: the root at index 0, an unused pad at
//! index 1 (an empty box, `min > max`), so that every sibling pair starts at an even index; an
//! inner node's two children are adjacent (`first`, `first + 1`); a leaf's triangles are
//! `primitive_indices[first .. first + count]` (original indices into `scene.triangles`).
//! [`Bvh::max_depth`] bounds the CPU traversal's stack. The GPU does not read these nodes: it
//! walks their four-wide collapse (`wide.rs`, uploaded by [`gpu::GpuBvh`] with the triangles in
//! leaf order, `scene.triangles[primitive_indices[i]]` at slot `i`).
//!
//! Build threading: obvhs's `parallel` feature is on (not on wasm32), so the build runs on every
//! core (250k triangles: 0.8 s on two cores in release) and gives the same tree on any number of
//! threads; queries are `&self` and meant to be spread over rays with rayon. [`BvhCache`] shares
//! one build among the renderers and references of one scene.

pub mod build;
mod cache;
pub mod camera_choice;
pub mod framing;
pub mod gpu;
mod traverse;
mod triangle;
pub mod wide;

#[cfg(test)]
mod tests;

use bytemuck::{Pod, Zeroable};
use glam::{Vec3, Vec3A, Vec4};

pub use cache::BvhCache;

use crate::scene::Scene;

/// A ray. `dir` need not be normalised: hit distances `t` are in units of `dir`, the hit point is
/// `origin + t * dir`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Ray origin, world space.
    pub origin: Vec3,
    /// Ray direction, world space; need not be normalised (it sets the unit of `t`).
    pub dir: Vec3,
}

impl Ray {
    /// The ray from `origin` along `dir`.
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Self { origin, dir }
    }

    /// The point at parameter `t`.
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.dir
    }
}

/// A ray/triangle hit that passed the scene's back-face and alpha rules.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Ray parameter, in units of `ray.dir`.
    pub t: f32,
    /// Index into `scene.triangles`.
    pub triangle: u32,
    /// Barycentric weight of the triangle's vertex 1.
    pub u: f32,
    /// Barycentric weight of the triangle's vertex 2 (vertex 0 has `1 - u - v`).
    pub v: f32,
    /// Counter-clockwise winding seen from the ray origin: `dot(dir, cross(p1-p0, p2-p0)) < 0`.
    pub front_face: bool,
}

/// What [`Bvh::for_each_hit`] does after reporting a hit (the shape of an any-hit shader).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HitAction {
    /// Keep looking in the current interval.
    Continue,
    /// Keep looking, but only up to this `t` (the new `t_max`; it never grows). `ShrinkTo(hit.t)`
    /// turns the traversal into a closest-hit search.
    ShrinkTo(f32),
    /// End the traversal.
    Stop,
}

/// One node of the flat BVH2, laid out for upload to a GPU storage buffer (32 bytes).
///
/// WGSL: `struct BvhNode { min: vec3<f32>, first: u32, max: vec3<f32>, count: u32 }`.
/// - `count == 0`: inner node; its children are `nodes[first]` and `nodes[first + 1]`.
/// - `count > 0`: leaf; its triangles are `primitive_indices[first .. first + count]`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct BvhNode {
    /// Minimum corner of the node's bounding box.
    pub min: [f32; 3],
    /// First child (inner node) or first slot in `primitive_indices` (leaf).
    pub first: u32,
    /// Maximum corner of the node's bounding box.
    pub max: [f32; 3],
    /// Number of triangles in a leaf; 0 for an inner node.
    pub count: u32,
}

impl BvhNode {
    /// Whether the node is a leaf (`count > 0`) rather than an inner node.
    pub fn is_leaf(&self) -> bool {
        self.count != 0
    }
}

/// The CPU traversal's copy of two sibling nodes (`nodes[2k]`, `nodes[2k + 1]`), transposed so both
/// boxes are tested with one set of 4-wide operations, in one 64-byte cache line.
/// Per axis: `[min_left, min_right, max_left, max_right]`.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(64))]
struct NodePair {
    x: Vec4,
    y: Vec4,
    z: Vec4,
    /// `[first_left, count_left, first_right, count_right]`, as in [`BvhNode`].
    link: [u32; 4],
}

/// A flat BVH2 over a scene's triangles (see the module documentation).
#[derive(Clone, Default)]
pub struct Bvh {
    /// GPU layout: the root, an unused pad, then sibling pairs. Empty without valid triangles.
    nodes: Vec<BvhNode>,
    /// The same tree for the CPU traversal: `pairs[k]` holds `nodes[2k]` and `nodes[2k + 1]`.
    pairs: Vec<NodePair>,
    /// Leaf order → index into `scene.triangles`.
    primitive_indices: Vec<u32>,
    /// Vertices of the triangles in leaf order (parallel to `primitive_indices`), so a leaf's
    /// triangles are read from one contiguous block instead of through two indirections.
    leaf_vertices: Vec<[Vec3A; 3]>,
    /// Depth of the deepest leaf (root = 0): the traversal stack never holds more entries.
    max_depth: usize,
    /// `scene.triangles.len()` at build time, to catch queries against another scene.
    scene_triangle_count: usize,
}

impl std::fmt::Debug for Bvh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Bvh")
            .field("nodes", &self.nodes.len())
            .field("triangles", &self.primitive_indices.len())
            .field("max_depth", &self.max_depth)
            .finish()
    }
}

impl Bvh {
    /// Builds the BVH over `scene.triangles` (see the module documentation for what is left out),
    /// at most [`build::MAX_DEPTH`] levels deep whatever the input, so no GPU traversal overflows
    /// its stack.
    pub fn build(scene: &Scene) -> Bvh {
        build::build(scene, build::Shape::Bounded(build::MAX_DEPTH))
    }

    /// [`Bvh::build`] without the depth bound: the SAH tree as it comes, however deep.
    pub fn build_unbounded(scene: &Scene) -> Bvh {
        build::build(scene, build::Shape::Unbounded)
    }

    /// The tree obvhs's own build makes, however deep: chains as deep as the triangle count on
    /// inputs its clustering stalls on (a polygon fan, duplicated or exponentially spaced
    /// triangles), which [`Bvh::build`] never makes. For tests of the traversal's overflow report.
    #[doc(hidden)]
    pub fn build_obvhs_unbounded(scene: &Scene) -> Bvh {
        build::build(scene, build::Shape::Obvhs)
    }

    /// The flat node array (empty for a scene without valid triangles): the root at index 0, an
    /// unused pad node at index 1 (an empty box: `min > max`), then sibling pairs at even indices.
    pub fn nodes(&self) -> &[BvhNode] {
        &self.nodes
    }

    /// Leaf slot → index into `scene.triangles`; leaves index this with `first .. first + count`.
    pub fn primitive_indices(&self) -> &[u32] {
        &self.primitive_indices
    }

    /// Number of triangles in the BVH (the scene's triangles minus the degenerate/invalid ones).
    pub fn triangle_count(&self) -> usize {
        self.primitive_indices.len()
    }

    /// Depth of the deepest leaf (root = 0); the CPU traversal's stack never holds more entries
    /// (the GPU's wide walk has its own bound, [`gpu::GpuBvh::stack_bound`]).
    pub fn max_depth(&self) -> usize {
        self.max_depth
    }

    /// The nearest hit with `t` in `[t_min, t_max]`, or `None`.
    pub fn closest_hit(&self, scene: &Scene, ray: &Ray, t_min: f32, t_max: f32) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        self.traverse(scene, ray, t_min, t_max, |hit| {
            // The traversal only reports hits with t <= the shrunk t_max, so on a tie the later one
            // wins; keep the first for a stable answer.
            if best.is_none_or(|b| hit.t < b.t) {
                best = Some(*hit);
            }
            HitAction::ShrinkTo(hit.t)
        });
        best
    }

    /// Whether any hit has `t` in `[t_min, t_max]` (stops at the first one found).
    pub fn any_hit(&self, scene: &Scene, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        let mut found = false;
        self.traverse(scene, ray, t_min, t_max, |_| {
            found = true;
            HitAction::Stop
        });
        found
    }

    /// Every hit with `t` in `[t_min, t_max]`, sorted by `t` (then triangle index). A ray exactly
    /// through a shared edge or vertex yields one hit per triangle touching it.
    pub fn all_hits(&self, scene: &Scene, ray: &Ray, t_min: f32, t_max: f32) -> Vec<Hit> {
        let mut hits = Vec::new();
        self.traverse(scene, ray, t_min, t_max, |hit| {
            hits.push(*hit);
            HitAction::Continue
        });
        hits.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.triangle.cmp(&b.triangle)));
        hits
    }

    /// Calls `f` for every hit with `t` in `[t_min, t_max]`, in traversal order (roughly near to
    /// far, not sorted); `f` decides whether to continue, shrink the interval's far end, or stop.
    pub fn for_each_hit(
        &self,
        scene: &Scene,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        f: impl FnMut(&Hit) -> HitAction,
    ) {
        self.traverse(scene, ray, t_min, t_max, f);
    }
}
