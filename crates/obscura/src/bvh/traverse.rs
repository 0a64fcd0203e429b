//! Stack-based BVH2 traversal with the scene's hit rules; every public query is a thin wrapper.
//!
//! Nearest child first: at an inner node both children's boxes are tested (one 4-wide test of the
//! sibling pair), the ray goes on with the child it enters first and pushes the other with its
//! entry distance, which is checked again on pop (the interval may have shrunk meanwhile). The GPU
//! walks the same boxes four at a time (`wide.rs`, `shaders/common/bvh.wgsl`), likewise
//! nearest child first, every pushed entry checked again on pop.

use glam::Vec2;

use super::{
    triangle::{loosen, RayPre, TriHit},
    Bvh, Hit, HitAction, Ray,
};
use crate::scene::{AlphaMode, Scene};

/// Stack entries kept on the (machine) stack; deeper trees fall back to a heap buffer.
const INLINE_STACK: usize = 64;

impl Bvh {
    /// Walks the BVH, calling `on_hit` for every hit in the current `[t_min, t_max]` that passes
    /// the scene's back-face and alpha rules.
    #[inline(always)]
    pub(super) fn traverse(
        &self,
        scene: &Scene,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        mut on_hit: impl FnMut(&Hit) -> HitAction,
    ) {
        if t_min.is_nan() || t_max.is_nan() || t_min > t_max || self.pairs.is_empty() {
            return;
        }
        debug_assert_eq!(
            scene.triangles.len(),
            self.scene_triangle_count,
            "BVH queried with a scene it was not built from"
        );
        let Some(pre) = RayPre::new(ray) else {
            return;
        };
        let mut t_max = t_max;
        // Boxes are culled against a slightly larger bound, so that rounding in the slab test never
        // drops a triangle whose own (differently rounded) t is still inside the interval.
        let mut t_cull = loosen(t_max);

        // Pending nodes: (node index, entry distance of its box).
        let mut inline_stack = [(0u32, 0f32); INLINE_STACK];
        let mut heap_stack;
        let stack: &mut [(u32, f32)] = if self.max_depth < INLINE_STACK {
            &mut inline_stack
        } else {
            heap_stack = vec![(0u32, 0f32); self.max_depth + 1];
            &mut heap_stack
        };
        let mut sp = 0usize;

        // Node `i`'s link (`first`, `count`) lives in pair `i / 2`, lane `i % 2`.
        let link = |node: usize| {
            let l = &self.pairs[node / 2].link;
            (l[2 * (node % 2)] as usize, l[2 * (node % 2) + 1] as usize)
        };

        // Pair 0 is [root, pad]; the pad's box is empty, so this starts with the root box test.
        let mut pair_index = 0usize;
        loop {
            // Test both children; descend into the nearer one that was hit and push the farther.
            let (mask, t_entry) = pre.pair_entry(&self.pairs[pair_index], t_min, t_cull);
            let mut node = match mask {
                1 => Some(2 * pair_index),
                2 => Some(2 * pair_index + 1),
                3 => {
                    let near = usize::from(t_entry[1] < t_entry[0]);
                    let far = 1 - near;
                    // At most one push per level, so `max_depth` entries suffice.
                    stack[sp] = ((2 * pair_index + far) as u32, t_entry[far]);
                    sp += 1;
                    Some(2 * pair_index + near)
                }
                _ => None,
            };
            loop {
                // Pop the next node that still overlaps the (possibly shrunk) interval.
                let current = match node.take() {
                    Some(n) => n,
                    None => loop {
                        if sp == 0 {
                            return;
                        }
                        sp -= 1;
                        let (index, t) = stack[sp];
                        if t <= t_cull {
                            break index as usize;
                        }
                    },
                };
                let (first, count) = link(current);
                if count == 0 {
                    pair_index = first / 2;
                    break;
                }
                for slot in first..first + count {
                    let Some(h) = pre.intersect(&self.leaf_vertices[slot], t_min, t_max) else {
                        continue;
                    };
                    let triangle = self.primitive_indices[slot];
                    if !passes_rules(scene, triangle, &h) {
                        continue;
                    }
                    let hit = Hit {
                        t: h.t,
                        triangle,
                        u: h.u,
                        v: h.v,
                        front_face: h.front_face,
                    };
                    match on_hit(&hit) {
                        HitAction::Continue => {}
                        HitAction::ShrinkTo(t) => {
                            // Never grows; a NaN request leaves the interval as it was.
                            if t < t_max {
                                t_max = t;
                                t_cull = loosen(t_max);
                            }
                            if t_max < t_min {
                                return;
                            }
                        }
                        HitAction::Stop => return,
                    }
                }
            }
        }
    }
}

/// The scene's rules for a geometric hit on `triangle`: back faces only where the material keeps
/// them, and the material's alpha test at the interpolated uv.
#[inline(always)]
pub(super) fn passes_rules(scene: &Scene, triangle: u32, h: &TriHit) -> bool {
    let material = scene
        .triangle_materials
        .get(triangle as usize)
        .and_then(|&m| scene.materials.get(m as usize));
    let Some(material) = material else {
        // No (valid) material: opaque and single-sided, like `Material::default()`.
        return h.front_face;
    };
    if !h.front_face && !material.keeps_back_faces() {
        return false;
    }
    // Only `Mask` materials can fail the alpha test; skip the uv interpolation for the rest.
    if !matches!(material.alpha_mode, AlphaMode::Mask { .. }) {
        return true;
    }
    material.passes_alpha_test(&scene.textures, hit_uv(scene, triangle, h.u, h.v))
}

/// Texture coordinate at barycentrics (u, v) of `triangle` (zero where `scene.uvs` has none).
pub(super) fn hit_uv(scene: &Scene, triangle: u32, u: f32, v: f32) -> Vec2 {
    let Some(tri) = scene.triangles.get(triangle as usize) else {
        return Vec2::ZERO;
    };
    let uv = |k: usize| {
        scene
            .uvs
            .get(tri[k] as usize)
            .copied()
            .unwrap_or(Vec2::ZERO)
    };
    uv(0) * (1.0 - u - v) + uv(1) * u + uv(2) * v
}
