//! The reference on demand: the ray-traced ground truth (the `vao` model, what VAO estimates with
//! nothing hidden) of the current view, traced on the CPU in a background thread so the window
//! stays interactive, with the row count as progress. The CPU tracer, not the GPU one: it does not
//! compete with the viewer for the queue, and on a software adapter it is the faster of the two
//! (see `reference --gpu`). Images are reused from and stored in the same cache as `reference`.

use obscura::bvh::BvhCache;
use obscura::reference::cache;
use obscura::reference::ground_truth::{
    render_reference_counted, ReferenceModel, ReferenceSettings,
};
use obscura::scene::{Camera, Scene};
use obscura::FrameView;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::mpsc::{channel, Receiver};
use std::sync::Arc;
use std::time::Instant;

/// A finished reference: the view it belongs to and its visible image.
pub struct ReferenceImage {
    pub camera: Camera,
    pub width: u32,
    pub height: u32,
    pub image: Vec<f32>,
    pub seconds: f64,
}

/// The reference being traced, if any, and the last one finished.
#[derive(Default)]
pub struct ReferenceJob {
    running: Option<Running>,
    pub done: Option<ReferenceImage>,
    pub error: Option<String>,
}

struct Running {
    rows: Arc<AtomicU32>,
    height: u32,
    result: Receiver<Result<ReferenceImage, String>>,
}

impl ReferenceJob {
    /// Start tracing `camera`'s view (a running job keeps going; its result is replaced).
    pub fn start(
        &mut self,
        scene: Arc<Scene>,
        bvh: BvhCache,
        camera: Camera,
        (width, height, guard_band): (u32, u32, u32),
        vao: obscura::settings::VaoSettings,
    ) {
        let rows = Arc::new(AtomicU32::new(0));
        let (send, result) = channel();
        let counter = rows.clone();
        std::thread::spawn(move || {
            let start = Instant::now();
            let view = FrameView::new(
                camera,
                width,
                height,
                guard_band,
                obscura::near_plane(&scene),
            );
            let settings = ReferenceSettings {
                model: ReferenceModel::Vao,
                vao,
                ..ReferenceSettings::default()
            };
            let dir = cache::cache_dir();
            let key = cache::key(&scene, &view, &settings);
            let pixels = (width * height) as usize;
            let image = match cache::load(&dir, &key, pixels) {
                Some(image) => image,
                None => {
                    let bvh = bvh.get(&scene);
                    let (image, _rays) =
                        render_reference_counted(&scene, &bvh, view, &settings, &|_| {
                            counter.fetch_add(1, Ordering::Relaxed);
                        });
                    if let Err(e) = cache::store(&dir, &key, &image) {
                        log::warn!("could not cache the reference: {e}");
                    }
                    image
                }
            };
            let _ = send.send(Ok(ReferenceImage {
                camera,
                width,
                height,
                image,
                seconds: start.elapsed().as_secs_f64(),
            }));
        });
        self.running = Some(Running {
            rows,
            height,
            result,
        });
        self.error = None;
    }

    /// Collect a finished job; the progress in [0, 1] while one runs.
    pub fn poll(&mut self) -> Option<f32> {
        let running = self.running.as_ref()?;
        match running.result.try_recv() {
            Ok(Ok(image)) => {
                self.done = Some(image);
                self.running = None;
                None
            }
            Ok(Err(e)) => {
                self.error = Some(e);
                self.running = None;
                None
            }
            Err(std::sync::mpsc::TryRecvError::Empty) => {
                Some(running.rows.load(Ordering::Relaxed) as f32 / running.height.max(1) as f32)
            }
            Err(std::sync::mpsc::TryRecvError::Disconnected) => {
                self.error = Some("the reference thread stopped without an image".into());
                self.running = None;
                None
            }
        }
    }

    /// The finished image if it belongs to this view and size.
    pub fn image_for(&self, camera: &Camera, width: u32, height: u32) -> Option<&[f32]> {
        self.done
            .as_ref()
            .filter(|r| r.camera == *camera && (r.width, r.height) == (width, height))
            .map(|r| r.image.as_slice())
    }
}
