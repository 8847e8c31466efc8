//! Soft shadows on planes: what share of an area light each floor pixel
//! sees.
//!
//! The light is a disc of angular radius [`LIGHT_RADIUS`] around the key
//! light's direction `l`, sampled at [`LIGHT_SAMPLES`] directions `lₖ`
//! spread over it evenly (Vogel's spiral: radius `√((k + ½)/K)`, angle
//! `k` times the golden angle). For each `lₖ` every facet that casts a
//! shadow is projected along `lₖ` onto the plane through `q` with normal
//! `n`,
//!
//! `p' = p − lₖ ((p − q)·n) / (lₖ·n)`,
//!
//! and the pixels its image covers are in that sample's shadow. A pixel's
//! shadow is the share of samples that shade it, box-blurred over a few
//! pixels to hide the steps between samples. The penumbra therefore
//! widens with the height of what casts it, as under a real area light:
//! the shadow is sharp where the cloth touches the floor and soft under
//! what hangs high. (Shadows cast onto the shadow casters themselves are
//! not drawn.)

use hooke_core::Vec3;

use crate::camera::Camera;
use crate::raster::{Vertex, cover};
use crate::tessellate::{Facet, basis};

/// Angular radius of the area light, radians (the sun's is 0.0047).
const LIGHT_RADIUS: f64 = 0.12;
/// Directions the area light is sampled in.
const LIGHT_SAMPLES: usize = 8;
/// Half-width of the box blur, in pixels per 480 pixels of the shorter
/// image side.
const BLUR: f64 = 2.0;

/// The share of the light each pixel of the camera's image misses on the
/// plane through `point` with unit `normal` lit from unit `light`: 0 in
/// full light, 1 in full shadow, row by row. `None` if the light is not
/// above the plane. (Pixels rather than the canvas's samples: the mask is
/// blurred anyway.)
pub(crate) fn shadow_mask(
    camera: &Camera,
    (point, normal): (Vec3, Vec3),
    light: Vec3,
    casters: &[Facet],
) -> Option<Vec<f32>> {
    if light.dot(&normal) <= 1e-3 {
        return None;
    }
    let (width, height) = (camera.width() as usize, camera.height() as usize);
    let (u, v) = basis(light);
    let mut shade = vec![0u16; width * height];
    // The last sample that shaded each pixel, so overlapping facets of one
    // sample count once.
    let mut stamp = vec![u16::MAX; width * height];
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    for k in 0..LIGHT_SAMPLES {
        let r = LIGHT_RADIUS * ((k as f64 + 0.5) / LIGHT_SAMPLES as f64).sqrt();
        let angle = golden * k as f64;
        let l = (light + (u * angle.cos() + v * angle.sin()) * r.tan()).normalize();
        let towards = l.dot(&normal);
        // A closed shape's outline is cast by its side facing the light
        // alone.
        for facet in casters
            .iter()
            .filter(|f| f.two_sided || f.normal.dot(&l) > 0.0)
        {
            let on_plane = facet.corners.map(|p| {
                let height = (p - point).dot(&normal).max(0.0);
                camera.project(p - l * (height / towards)).map(|q| Vertex {
                    x: q.x,
                    y: q.y,
                    inv_depth: 1.0,
                })
            });
            let [Some(a), Some(b), Some(c)] = on_plane else {
                continue;
            };
            let sample = k as u16;
            cover([a, b, c], width, height, |index, _| {
                if stamp[index] != sample {
                    stamp[index] = sample;
                    shade[index] += 1;
                }
            });
        }
    }
    let mut mask: Vec<f32> = shade
        .iter()
        .map(|&s| f32::from(s) / LIGHT_SAMPLES as f32)
        .collect();
    let radius = (BLUR * width.min(height) as f64 / 480.0).round() as usize;
    box_blur(&mut mask, width, height, radius.max(1));
    Some(mask)
}

/// Two passes of a box blur of half-width `radius` along rows, then along
/// columns: close to a Gaussian.
fn box_blur(values: &mut [f32], width: usize, height: usize, radius: usize) {
    let mut line = Vec::new();
    for _ in 0..2 {
        for y in 0..height {
            blur_line(values, y * width, 1, width, radius, &mut line);
        }
        for x in 0..width {
            blur_line(values, x, width, height, radius, &mut line);
        }
    }
}

/// Replaces the `len` values at `start`, `start + stride`, ... by their
/// means over windows of `2 radius + 1`, cut at the ends.
fn blur_line(
    values: &mut [f32],
    start: usize,
    stride: usize,
    len: usize,
    radius: usize,
    line: &mut Vec<f32>,
) {
    line.clear();
    line.extend((0..len).map(|i| values[start + i * stride]));
    let mut sum: f32 = line[..radius.min(len)].iter().sum();
    for i in 0..len {
        if i + radius < len {
            sum += line[i + radius];
        }
        if i > radius {
            sum -= line[i - radius - 1];
        }
        let window = (i + radius).min(len - 1) + 1 - i.saturating_sub(radius);
        values[start + i * stride] = sum / window as f32;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blurring_keeps_a_constant_and_spreads_a_spike_evenly() {
        let mut flat = vec![0.5f32; 7 * 5];
        box_blur(&mut flat, 7, 5, 2);
        assert!(flat.iter().all(|&v| (v - 0.5).abs() < 1e-6));

        let mut spike = vec![0.0f32; 21];
        spike[10] = 1.0;
        let (mut line, stride) = (Vec::new(), 1);
        blur_line(&mut spike, 0, stride, 21, 2, &mut line);
        for (i, &v) in spike.iter().enumerate() {
            let expected = if (8..=12).contains(&i) { 0.2 } else { 0.0 };
            assert!((v - expected).abs() < 1e-6, "{i}: {v}");
        }
    }
}
