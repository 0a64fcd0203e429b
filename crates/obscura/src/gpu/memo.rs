//! Shader modules, bind group layouts, pipeline layouts and compute pipelines made once per
//! device and reused by every renderer made on it.
//!
//! A renderer compiles a dozen or more pipelines, and most of them are the same from one
//! renderer to the next: the filters, the G-buffer helpers, and the AO kernels whenever only
//! uniform values (a radius, a thickness) change. Compiling them is most of what making a
//! renderer costs (on Mesa's lavapipe two thirds of the CPU time of the tests' settings sweep
//! went into the driver, most of the rest into wgpu's WGSL translation and allocations), and a
//! program that makes several renderers (a settings sweep, a dataset writing several rows,
//! Python calls) pays it again each time. wgpu deduplicates nothing of this itself, so
//! obscura keeps what it made, by content: the same WGSL and runtime checks give the same module,
//! the same entries the same bind group layout, the same module, entry point, override constants
//! and layouts the same pipeline.
//!
//! What is kept belongs to a [`Gpu`](super::Gpu) (shared by its clones, released with the last
//! one) and is used in the scope [`Gpu::keeping`](super::Gpu::keeping) opens, which the
//! constructors of renderers and passes open first: the creation functions below find it there, as they are handed a
//! `wgpu::Device` only. (wgpu's handles compare by an id that is unique only within one
//! `wgpu::Instance`, so a process-wide table keyed by device could mix up two devices of two
//! instances; a scope names the device's own table.) Outside a scope, or for another device,
//! nothing is kept. A creation during which the device raised a validation error is not kept,
//! so that a failure is reported again the next time, as it was the first. On the web (wasm32)
//! nothing is kept: there, errors arrive later, asynchronously.
//!
//! Nothing is evicted: every distinct pipeline (each set of override constants a setting such as a
//! sample count makes) stays until its `Gpu` goes. Those sets are few, and a pipeline is small
//! beside the images a renderer allocates.

use std::cell::RefCell;
use std::collections::HashMap;
use std::hash::Hash;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// What one device's renderers share.
pub(crate) struct Kept {
    device: wgpu::Device,
    /// How many errors the device has raised: read before and after a creation.
    errors_raised: Arc<AtomicU64>,
    maps: Mutex<Maps>,
}

#[derive(Default)]
struct Maps {
    modules: HashMap<(String, String), wgpu::ShaderModule>,
    bind_group_layouts: HashMap<Vec<wgpu::BindGroupLayoutEntry>, wgpu::BindGroupLayout>,
    pipeline_layouts: HashMap<Vec<Option<wgpu::BindGroupLayout>>, wgpu::PipelineLayout>,
    pipelines: HashMap<PipelineKey, wgpu::ComputePipeline>,
}

/// A compute pipeline by what it is made of: module, entry point, override constants (by bit
/// pattern) and layout (`None`: derived from the shader).
#[derive(PartialEq, Eq, Hash)]
pub(crate) struct PipelineKey {
    pub module: wgpu::ShaderModule,
    pub entry: String,
    pub constants: Vec<(String, u64)>,
    pub layout: Option<wgpu::PipelineLayout>,
}

impl Kept {
    /// An empty table for `device`, whose uncaptured-error handler adds one to `errors_raised`
    /// for each error.
    pub(crate) fn new(device: &wgpu::Device, errors_raised: Arc<AtomicU64>) -> Kept {
        Kept {
            device: device.clone(),
            errors_raised,
            maps: Mutex::new(Maps::default()),
        }
    }

    /// The counter the device's error handler adds to ([`crate::Gpu::from_device`] installs it).
    pub(crate) fn errors_raised(&self) -> Arc<AtomicU64> {
        self.errors_raised.clone()
    }

    /// Drops everything kept (what `Gpu::forget_kept` does).
    pub(crate) fn forget(&self) {
        *self.maps() = Maps::default();
    }

    /// Locked; a thread that panicked while holding the lock left the maps whole (nothing here
    /// panics midway through a change), so the lock is taken anyway.
    fn maps(&self) -> std::sync::MutexGuard<'_, Maps> {
        self.maps.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// How many compute pipelines are kept (tests).
    #[cfg(test)]
    pub(crate) fn pipelines(&self) -> usize {
        self.maps().pipelines.len()
    }
}

thread_local! {
    /// The table of this thread's innermost [`Scope`].
    static CURRENT: RefCell<Option<Arc<Kept>>> = const { RefCell::new(None) };
}

/// This thread's table from [`enter`] until dropped, when the one before is back (scopes nest).
/// Not `Send`: it restores the thread it was made on.
pub(crate) struct Scope {
    previous: Option<Arc<Kept>>,
    _this_thread: std::marker::PhantomData<*const ()>,
}

/// Makes `kept` this thread's table until the returned scope is dropped.
pub(crate) fn enter(kept: &Arc<Kept>) -> Scope {
    Scope {
        previous: CURRENT.with(|c| c.borrow_mut().replace(kept.clone())),
        _this_thread: std::marker::PhantomData,
    }
}

impl Drop for Scope {
    fn drop(&mut self) {
        CURRENT.with(|c| *c.borrow_mut() = self.previous.take());
    }
}

/// The value kept for `key` in the map `map` picks, or `make`'s, kept when this thread is
/// inside a [`Scope`] for `device` (compared by wgpu's id, unique within one instance: every
/// creation inside a scope is on the scope's device) and the device raised no error while
/// `make` ran (an error another thread raised meanwhile also counts: then nothing is kept). The
/// lock is not held while `make` runs: two threads may make the same thing at once, and then
/// the first one kept is used from then on.
fn kept_or_make<K: Eq + Hash, V: Clone>(
    device: &wgpu::Device,
    map: impl Fn(&mut Maps) -> &mut HashMap<K, V>,
    key: K,
    make: impl FnOnce() -> V,
) -> V {
    let kept = CURRENT.with(|c| c.borrow().clone());
    let Some(kept) = kept.filter(|k| k.device == *device && !cfg!(target_arch = "wasm32")) else {
        return make();
    };
    if let Some(value) = map(&mut kept.maps()).get(&key) {
        return value.clone();
    }
    let raised = kept.errors_raised.load(Ordering::SeqCst);
    let value = make();
    if kept.errors_raised.load(Ordering::SeqCst) != raised {
        return value;
    }
    let kept_value = map(&mut kept.maps()).entry(key).or_insert(value).clone();
    kept_value
}

/// The shader module of `source` with runtime checks `checks` (their `Debug` text: wgpu's type
/// has no `Hash`), made by `make` the first time.
pub(crate) fn module(
    device: &wgpu::Device,
    source: &str,
    checks: &str,
    make: impl FnOnce() -> wgpu::ShaderModule,
) -> wgpu::ShaderModule {
    kept_or_make(
        device,
        |k| &mut k.modules,
        (source.to_owned(), checks.to_owned()),
        make,
    )
}

/// The bind group layout of `entries`, made by `make` the first time.
pub(crate) fn bind_group_layout(
    device: &wgpu::Device,
    entries: &[wgpu::BindGroupLayoutEntry],
    make: impl FnOnce() -> wgpu::BindGroupLayout,
) -> wgpu::BindGroupLayout {
    kept_or_make(
        device,
        |k| &mut k.bind_group_layouts,
        entries.to_vec(),
        make,
    )
}

/// The pipeline layout of `groups`, made by `make` the first time.
pub(crate) fn pipeline_layout(
    device: &wgpu::Device,
    groups: &[Option<&wgpu::BindGroupLayout>],
    make: impl FnOnce() -> wgpu::PipelineLayout,
) -> wgpu::PipelineLayout {
    let key = groups.iter().map(|g| g.cloned()).collect();
    kept_or_make(device, |k| &mut k.pipeline_layouts, key, make)
}

/// The compute pipeline `key` describes, made by `make` the first time.
pub(crate) fn compute_pipeline(
    device: &wgpu::Device,
    key: PipelineKey,
    make: impl FnOnce() -> wgpu::ComputePipeline,
) -> wgpu::ComputePipeline {
    kept_or_make(device, |k| &mut k.pipelines, key, make)
}

#[cfg(test)]
mod tests {
    use crate::gpu::{compute_pipeline_with, Gpu, GpuOptions};

    const SOURCE: &str = "override scale: f32 = 1.0;
        @group(0) @binding(0) var<storage, read_write> out: array<f32>;
        @compute @workgroup_size(1) fn main() { out[0] = scale; }";

    fn pipeline(gpu: &Gpu, scale: f64) -> wgpu::ComputePipeline {
        compute_pipeline_with(&gpu.device, "memo test", SOURCE, &[("scale", scale)])
    }

    #[test]
    fn a_gpu_makes_the_same_pipeline_once_and_only_inside_its_scope() {
        let gpu = Gpu::new(&GpuOptions::default()).unwrap();
        let scope = gpu.keeping();
        let (a, b, c) = (
            pipeline(&gpu, 2.0),
            pipeline(&gpu, 2.0),
            pipeline(&gpu, 3.0),
        );
        drop(scope);
        assert!(a == b, "the second request gets the first pipeline");
        assert!(a != c, "other constants, another pipeline");
        assert_eq!(gpu.kept.pipelines(), 2);
        // Later constructors on the same Gpu (or a clone) reuse it.
        let clone = gpu.clone();
        {
            let _scope = clone.keeping();
            assert!(pipeline(&clone, 2.0) == a);
        }
        // Outside a scope nothing is kept or reused.
        let outside = pipeline(&gpu, 2.0);
        assert!(outside != a);
        assert_eq!(gpu.kept.pipelines(), 2);
        // Another Gpu keeps its own. (Within one scope, everything is made on the scope's
        // device: constructors make things on their own Gpu's device only. wgpu's handles of two
        // instances may compare equal, so the check that a device is the scope's cannot tell
        // them apart.)
        let other = Gpu::new(&GpuOptions::default()).unwrap();
        assert_eq!(other.kept.pipelines(), 0);
        // Scopes nest, and the outer one is back after the inner ends.
        {
            let _outer = gpu.keeping();
            {
                let _inner = other.keeping();
                pipeline(&other, 2.0);
            }
            assert!(pipeline(&gpu, 3.0) == c);
        }
        assert_eq!(other.kept.pipelines(), 1);
        gpu.finish().unwrap();
        other.finish().unwrap();
    }

    #[test]
    fn a_creation_that_raised_an_error_is_not_kept_and_fails_again() {
        let gpu = Gpu::new(&GpuOptions::default()).unwrap();
        // A valid module (the WGSL dump of OBSCURA_DUMP_WGSL, which CI translates for Metal and
        // DirectX, must hold only valid WGSL) and an entry point it does not have: a validation
        // error of the pipeline's creation. (Its label differs from the module's, so no
        // constants file names that entry point beside the dumped module.)
        for attempt in 0..2 {
            let _scope = gpu.keeping();
            let module = crate::gpu::shader_module(&gpu.device, "memo test", SOURCE);
            crate::gpu::entry_pipeline(&gpu.device, "memo refused", &module, "absent", &[], None);
            let error = gpu.finish().unwrap_err().to_string();
            assert!(error.contains("memo refused"), "attempt {attempt}: {error}");
        }
        assert_eq!(gpu.kept.pipelines(), 0);
    }
}
