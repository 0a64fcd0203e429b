//! The bilateral blur of `shaders/filter/bilateral_blur.wgsl` on the CPU: a test oracle.

use crate::raster::GBufferImage;
use crate::settings::BlurSettings;
use crate::view::ScreenGeometry;

/// One pass along `direction` ((1, 0) or (0, 1)) of a visible-size AO image.
fn blur_pass(
    ao: &[f32],
    g: &GBufferImage,
    screen: &ScreenGeometry,
    s: &BlurSettings,
    direction: (i32, i32),
) -> Vec<f32> {
    let (w, h) = (screen.width as i32, screen.height as i32);
    let band = screen.guard_band as i32;
    let depth = |x: i32, y: i32| {
        let fx = (x + band).clamp(0, g.width as i32 - 1);
        let fy = (y + band).clamp(0, g.height as i32 - 1);
        g.depth[(fy * g.width as i32 + fx) as usize]
    };
    let r = s.radius as i32;
    let falloff = s.falloff();
    let mut out = vec![0.0; ao.len()];
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            let z = depth(x, y);
            if z <= 0.0 {
                out[i] = ao[i];
                continue;
            }
            let (dx, dy) = direction;
            let forward = depth(x + dx, y + dy) - z;
            let backward = z - depth(x - dx, y - dy);
            let slope = if forward.abs() < backward.abs() {
                forward
            } else {
                backward
            };
            let (mut sum, mut weight_sum) = (ao[i], 1.0f32);
            for d in -r..=r {
                let (qx, qy) = (x + dx * d, y + dy * d);
                if d == 0 || qx < 0 || qy < 0 || qx >= w || qy >= h {
                    continue;
                }
                let zq = depth(qx, qy);
                if zq <= 0.0 {
                    continue;
                }
                let dz = (zq - z - slope * d as f32) * s.sharpness;
                let weight = (-((d * d) as f32) * falloff - dz * dz).exp2();
                sum += weight * ao[(qy * w + qx) as usize];
                weight_sum += weight;
            }
            out[i] = sum / weight_sum;
        }
    }
    out
}

/// Both passes, x then y.
pub fn cpu_blur(
    ao: &[f32],
    g: &GBufferImage,
    screen: &ScreenGeometry,
    s: &BlurSettings,
) -> Vec<f32> {
    let x = blur_pass(ao, g, screen, s, (1, 0));
    blur_pass(&x, g, screen, s, (0, 1))
}
