//! [`Canvas`]: the renderer's supersampled colour and depth buffers, filled
//! triangle by triangle with a depth test, and resolved to a [`Pixmap`].
//!
//! A triangle covers the samples whose centres lie inside it or on its
//! edges, found with the three edge functions `wₖ(p)`, whose ratios to the
//! doubled area are the screen-space barycentric coordinates `bₖ`. Depth is
//! tested on `1/z`, which is affine in screen space; attributes are
//! interpolated perspective-correctly with the weights `bₖ (1/zₖ) / (1/z)`.
//! Each output pixel averages [`SUPERSAMPLE`]² samples, which anti-aliases
//! every edge, the silhouettes included.

use tiny_skia::{ColorU8, Pixmap};

/// Samples per pixel along each axis.
pub(crate) const SUPERSAMPLE: usize = 2;

/// Steps of the table from linear light to sRGB.
const SRGB_STEPS: usize = 4095;

/// A linear RGB colour, each channel in [0, 1].
pub(crate) type Linear = [f32; 3];

/// A vertex on the canvas: sample coordinates (x right, y down) and the
/// inverse of its depth along the viewing direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Vertex {
    pub x: f64,
    pub y: f64,
    pub inv_depth: f64,
}

/// The samples a triangle covers, as `(index, barycentric weights)` with the
/// weights summing to one; nothing for a degenerate triangle.
///
/// `width` and `height` are the sample grid's; `index = y · width + x`.
pub(crate) fn cover(
    corners: [Vertex; 3],
    width: usize,
    height: usize,
    mut visit: impl FnMut(usize, [f64; 3]),
) {
    let [a, b, c] = corners;
    let area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if area.abs() <= f64::EPSILON || !area.is_finite() {
        return;
    }
    // wₖ(p) = Aₖ x + Bₖ y + Cₖ, the edge opposite corner k, scaled so that
    // the three sum to one.
    let edge = |p: Vertex, q: Vertex| {
        let (ea, eb) = ((p.y - q.y) / area, (q.x - p.x) / area);
        (ea, eb, -(ea * p.x + eb * p.y))
    };
    let edges = [edge(b, c), edge(c, a), edge(a, b)];
    let span = |lo: f64, hi: f64, limit: usize| {
        let first = (lo - 0.5).ceil().max(0.0);
        let last = (hi - 0.5).floor().min(limit as f64 - 1.0);
        (first <= last).then_some((first as usize, last as usize))
    };
    let Some((x0, x1)) = span(a.x.min(b.x).min(c.x), a.x.max(b.x).max(c.x), width) else {
        return;
    };
    let Some((y0, y1)) = span(a.y.min(b.y).min(c.y), a.y.max(b.y).max(c.y), height) else {
        return;
    };
    for y in y0..=y1 {
        let py = y as f64 + 0.5;
        // Along the row each wₖ = Aₖ x + (Bₖ y + Cₖ) is affine in x, so the
        // samples inside lie between the bounds the three set: only those
        // are visited, however thin and slanted the triangle.
        let (mut lo, mut hi) = (x0 as f64 + 0.5, x1 as f64 + 0.5);
        for &(ea, eb, ec) in &edges {
            let rest = eb * py + ec;
            if ea > 0.0 {
                lo = lo.max(-rest / ea);
            } else if ea < 0.0 {
                hi = hi.min(-rest / ea);
            } else if rest < 0.0 {
                hi = f64::NEG_INFINITY;
            }
        }
        let Some((first, last)) = span(lo, hi, width) else {
            continue;
        };
        for x in first.max(x0)..=last.min(x1) {
            let px = x as f64 + 0.5;
            let w = edges.map(|(ea, eb, ec)| ea * px + eb * py + ec);
            // Rounding at the interval's ends can leave a weight a hair
            // below zero; the interval already decided the sample is in.
            visit(y * width + x, w.map(|wk| wk.max(0.0)));
        }
    }
}

/// Colour and depth samples of one picture.
#[derive(Clone)]
pub(crate) struct Canvas {
    width: usize,
    height: usize,
    color: Vec<Linear>,
    /// `1/z` of the nearest surface drawn at each sample, 0 where none is.
    depth: Vec<f64>,
}

impl Canvas {
    /// A canvas for a picture of `width` x `height` pixels, every sample
    /// coloured by `background(y)` for its row `y` in [0, 1] (top to
    /// bottom) and as far as can be.
    pub(crate) fn new(width: u32, height: u32, background: impl Fn(f32) -> Linear) -> Self {
        let (width, height) = (width as usize * SUPERSAMPLE, height as usize * SUPERSAMPLE);
        let color = (0..height)
            .flat_map(|y| {
                let row = background((y as f32 + 0.5) / height as f32);
                std::iter::repeat_n(row, width)
            })
            .collect();
        Self {
            width,
            height,
            color,
            depth: vec![0.0; width * height],
        }
    }

    /// Width and height in samples.
    pub(crate) fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// Draws a triangle with depth test: at every covered sample nearer
    /// than what is there, `shade` gets the sample's index and the
    /// perspective-correct barycentric weights and returns the colour.
    pub(crate) fn triangle(
        &mut self,
        corners: [Vertex; 3],
        mut shade: impl FnMut(usize, [f64; 3]) -> Linear,
    ) {
        let (width, height) = (self.width, self.height);
        let inv = corners.map(|v| v.inv_depth);
        cover(corners, width, height, |index, b| {
            let inv_depth = b[0] * inv[0] + b[1] * inv[1] + b[2] * inv[2];
            if inv_depth > self.depth[index] {
                self.depth[index] = inv_depth;
                let weights = [0, 1, 2].map(|k| b[k] * inv[k] / inv_depth);
                self.color[index] = shade(index, weights);
            }
        });
    }

    /// Scales the colour of the sample at `index` by `factor`.
    pub(crate) fn darken(&mut self, index: usize, factor: f32) {
        for channel in &mut self.color[index] {
            *channel *= factor;
        }
    }

    /// The picture: each pixel the mean of its samples, in sRGB.
    pub(crate) fn resolve(&self) -> Option<Pixmap> {
        let (w, h) = (self.width / SUPERSAMPLE, self.height / SUPERSAMPLE);
        let mut pixmap = Pixmap::new(u32::try_from(w).ok()?, u32::try_from(h).ok()?)?;
        let scale = 1.0 / (SUPERSAMPLE * SUPERSAMPLE) as f32;
        // sRGB of linear light in steps of 1/4095: finer than the 8-bit
        // output resolves, and cheaper than a power per channel.
        let table: Vec<u8> = (0..=SRGB_STEPS)
            .map(|i| to_srgb(i as f32 / SRGB_STEPS as f32))
            .collect();
        let srgb = |linear: f32| table[(linear.clamp(0.0, 1.0) * SRGB_STEPS as f32 + 0.5) as usize];
        for (i, pixel) in pixmap.pixels_mut().iter_mut().enumerate() {
            let (x, y) = (i % w * SUPERSAMPLE, i / w * SUPERSAMPLE);
            let mut sum = [0.0f32; 3];
            for sy in y..y + SUPERSAMPLE {
                for sample in &self.color[sy * self.width + x..][..SUPERSAMPLE] {
                    for (s, c) in sum.iter_mut().zip(sample) {
                        *s += c;
                    }
                }
            }
            let [r, g, b] = sum.map(|s| srgb(s * scale));
            *pixel = ColorU8::from_rgba(r, g, b, 255).premultiply();
        }
        Some(pixmap)
    }
}

/// An 8-bit sRGB channel as linear light.
pub(crate) fn to_linear(channel: u8) -> f32 {
    let c = f32::from(channel) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear light as an 8-bit sRGB channel.
fn to_srgb(linear: f32) -> u8 {
    let c = linear.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).round() as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vertex(x: f64, y: f64) -> Vertex {
        Vertex {
            x,
            y,
            inv_depth: 1.0,
        }
    }

    #[test]
    fn a_triangle_covers_half_its_bounding_square_and_weights_sum_to_one() {
        let mut count = 0;
        cover(
            [vertex(0.0, 0.0), vertex(100.2, 0.0), vertex(0.0, 100.2)],
            200,
            200,
            |_, w| {
                count += 1;
                assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            },
        );
        // Sample centres (i + ½, j + ½) with i + j + 1 ≤ 100.2: 100·101/2.
        assert_eq!(count, 5050);
    }

    #[test]
    fn srgb_round_trips_every_channel() {
        for c in 0..=255u8 {
            assert_eq!(to_srgb(to_linear(c)), c);
        }
    }

    #[test]
    fn the_nearer_triangle_wins_whatever_the_order() {
        let square = |inv_depth| {
            [(0.0, 0.0), (4.0, 0.0), (0.0, 4.0)].map(|(x, y)| Vertex { x, y, inv_depth })
        };
        for order in [[0.5, 0.25], [0.25, 0.5]] {
            let mut canvas = Canvas::new(2, 2, |_| [0.0; 3]);
            for inv in order {
                canvas.triangle(square(inv), |_, _| [inv as f32; 3]);
            }
            assert!((canvas.color[0][0] - 0.5).abs() < 1e-6);
        }
    }
}
