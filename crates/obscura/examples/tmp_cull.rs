// Throwaway: how many of Sponza's triangles a compute cull would remove (not committed).
use glam::{Vec3, Vec4Swizzles};
use obscura::scene::{self, Camera};
fn main() {
    let s = scene::load(&std::env::args().nth(1).unwrap()).unwrap();
    let cam = Camera::new(Vec3::new(-9.5, 1.8, -0.4), Vec3::new(0.0, 3.5, 0.6), 60.0).unwrap();
    let (w, h, band) = (1920u32, 1080u32, 64u32);
    let view = obscura::FrameView::new(cam, w, h, band, obscura::view::near_plane(&s));
    let m = view.projection() * view.view_matrix();
    let (fw, fh) = ((w + 2 * band) as f32, (h + 2 * band) as f32);
    let (mut outside, mut back, mut tiny, mut near, mut kept, mut culled_group) =
        (0, 0, 0, 0, 0, 0);
    for (t, tri) in s.triangles.iter().enumerate() {
        let mat = &s.materials[s.triangle_materials[t] as usize];
        let c: Vec<_> = tri
            .iter()
            .map(|&i| m * s.positions[i as usize].extend(1.0))
            .collect();
        // frustum: all outside one plane
        let out = |f: &dyn Fn(glam::Vec4) -> bool| c.iter().all(|v| f(*v));
        if out(&|v| v.x > v.w)
            || out(&|v| v.x < -v.w)
            || out(&|v| v.y > v.w)
            || out(&|v| v.y < -v.w)
            || out(&|v| v.z > v.w)
            || out(&|v| v.w <= 0.0)
        {
            outside += 1;
            continue;
        }
        if c.iter().any(|v| v.w <= 0.0) {
            near += 1;
            kept += 1;
            continue;
        }
        let p: Vec<_> = c
            .iter()
            .map(|v| {
                let n = v.xy() / v.w;
                glam::Vec2::new((n.x * 0.5 + 0.5) * fw, (0.5 - n.y * 0.5) * fh)
            })
            .collect();
        let area = (p[1] - p[0]).perp_dot(p[2] - p[0]);
        let culled = !mat.double_sided;
        if culled {
            culled_group += 1;
        }
        // y flipped: ccw in NDC is cw in pixels
        if culled && area > 0.0 {
            back += 1;
            continue;
        }
        let lo = p[0].min(p[1]).min(p[2]);
        let hi = p[0].max(p[1]).max(p[2]);
        // any pixel centre (x+0.5) inside bbox?
        let cx = (lo.x - 0.5).ceil() <= (hi.x - 0.5).floor();
        let cy = (lo.y - 0.5).ceil() <= (hi.y - 0.5).floor();
        if !(cx && cy) {
            tiny += 1;
            continue;
        }
        kept += 1;
    }
    println!("triangles {} outside {} back {} no-pixel-centre-bbox {} crossing-near {} kept {} (culled-material tris in view {})",
        s.triangles.len(), outside, back, tiny, near, kept, culled_group);
}
