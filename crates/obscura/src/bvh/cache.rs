//! One scene's BVH, built once for every renderer and reference that asks for it.
//!
//! A BVH depends on the scene's positions and triangles alone, and building one is the slow step
//! of bringing a large scene to a ray-traced technique (two million triangles: about 6 s on two
//! cores). `compare` makes one renderer per technique and a reference, `path` a reference per
//! frame, the viewer a renderer per technique switch: without a shared cache each of them built
//! the same tree again.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

use super::Bvh;
use crate::hash::Fnv1a;
use crate::scene::Scene;

/// The last scene's BVH, shared: [`BvhCache::get`] returns it while the scene's positions and
/// triangles are those it was built from, and builds (and keeps) a new one when they are not.
/// Cloning the cache shares it. It holds one tree at a time, so a cache kept alive keeps that
/// tree's memory (about 100 bytes a triangle) until it is dropped or another scene replaces it.
#[derive(Clone, Debug, Default)]
pub struct BvhCache {
    inner: Arc<Inner>,
}

#[derive(Debug, Default)]
struct Inner {
    last: Mutex<Option<(u64, Arc<Bvh>)>>,
    builds: AtomicUsize,
}

impl BvhCache {
    /// An empty cache.
    pub fn new() -> Self {
        Self::default()
    }

    /// `scene`'s BVH ([`Bvh::build`]): the kept one when it was built over the same positions and
    /// triangles (compared by a 64-bit FNV-1a hash of their bytes: about 18 bytes a triangle of a
    /// closed mesh, hashed at roughly 1 GB/s as for [`Scene::fingerprint`]), else a new one, which
    /// replaces it.
    pub fn get(&self, scene: &Scene) -> Arc<Bvh> {
        let key = geometry_key(scene);
        // A panic elsewhere while the lock was held leaves at worst a stale entry whose key
        // still describes its tree, so a poisoned lock is safe to take.
        let mut last = self
            .inner
            .last
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        if let Some((k, bvh)) = last.as_ref() {
            if *k == key {
                return bvh.clone();
            }
        }
        // The old tree goes before the new one is built, so the two are never held together.
        *last = None;
        let bvh = Arc::new(Bvh::build(scene));
        self.inner.builds.fetch_add(1, Ordering::Relaxed);
        *last = Some((key, bvh.clone()));
        bvh
    }

    /// How many trees this cache (and its clones) has built.
    pub fn builds(&self) -> usize {
        self.inner.builds.load(Ordering::Relaxed)
    }
}

/// A hash of what a BVH is built from: the positions and the triangles (not the materials,
/// uvs or textures, which are read from the scene at hit time).
fn geometry_key(scene: &Scene) -> u64 {
    let mut hash = Fnv1a::default();
    hash.bytes(&(scene.positions.len() as u64).to_le_bytes());
    hash.bytes(bytemuck::cast_slice(&scene.positions));
    hash.bytes(bytemuck::cast_slice(&scene.triangles));
    hash.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin;

    #[test]
    fn the_same_geometry_is_built_once_and_shared() {
        let stairs = builtin("stairs").unwrap();
        let cache = BvhCache::new();
        let first = cache.get(&stairs);
        // Another copy of the scene, through a clone of the cache: the same tree.
        let again = cache.clone().get(&stairs.clone());
        assert!(Arc::ptr_eq(&first, &again));
        assert_eq!(cache.builds(), 1);
        // Materials are read at hit time: a scene differing only there keeps the tree.
        let mut retinted = stairs.clone();
        retinted.materials[0].base_color = [0.1, 0.2, 0.3, 1.0];
        assert!(Arc::ptr_eq(&first, &cache.get(&retinted)));
        assert_eq!(cache.builds(), 1);
    }

    #[test]
    fn other_geometry_is_built_again_and_equals_a_fresh_build() {
        let stairs = builtin("stairs").unwrap();
        let cache = BvhCache::new();
        let first = cache.get(&stairs);
        let mut moved = stairs.clone();
        moved.positions[0].y += 0.25;
        let second = cache.get(&moved);
        assert!(!Arc::ptr_eq(&first, &second));
        assert_eq!(cache.builds(), 2);
        let fresh = Bvh::build(&moved);
        assert_eq!(
            bytemuck::cast_slice::<_, u8>(second.nodes()),
            bytemuck::cast_slice::<_, u8>(fresh.nodes())
        );
        assert_eq!(second.primitive_indices(), fresh.primitive_indices());
        // Back to the first scene: the cache held one tree, so it builds again.
        let third = cache.get(&stairs);
        assert_eq!(cache.builds(), 3);
        assert_eq!(third.primitive_indices(), first.primitive_indices());
    }
}
