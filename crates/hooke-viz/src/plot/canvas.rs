//! A pixmap with the few drawing operations the figures use: filled
//! rectangles, poly-lines, markers and text in the embedded 8×8 bitmap font;
//! each operation is also recorded as SVG ([`Svg`]).

use super::svg::Svg;
use font8x8::{BASIC_FONTS, GREEK_FONTS, LATIN_FONTS, UnicodeFonts};
use tiny_skia::{
    Color, ColorU8, FillRule, LineCap, LineJoin, Paint, PathBuilder, Pixmap, Rect, Stroke,
    StrokeDash, Transform,
};

/// Side of a glyph cell of the bitmap font, in font pixels.
const GLYPH: u32 = 8;

/// Text size for tick labels, legends and axis titles: each font pixel is a
/// square of this many image pixels, so a character is 16 pixels wide and high.
pub(super) const TEXT: u32 = 2;
/// Text size for figure titles (24-pixel characters).
pub(super) const TITLE: u32 = 3;

/// The largest image drawn, in pixels (256 MiB of RGBA).
pub(super) const MAX_PIXELS: u64 = 64 << 20;

/// Where a text's anchor point lies along the text.
#[derive(Clone, Copy)]
pub(super) enum Align {
    /// The anchor is the text's start.
    Start,
    /// The anchor is the text's middle.
    Middle,
    /// The anchor is the text's end.
    End,
}

/// The marker shapes that tell series apart besides their colour.
#[derive(Clone, Copy)]
pub(super) enum Marker {
    Circle,
    Square,
    Triangle,
    Diamond,
}

impl Marker {
    /// The shapes in the order series use them.
    pub(super) const ALL: [Self; 4] = [Self::Circle, Self::Square, Self::Triangle, Self::Diamond];
}

/// An opaque colour from its 8-bit channels.
pub(super) const fn rgb(r: u8, g: u8, b: u8) -> ColorU8 {
    ColorU8::from_rgba(r, g, b, 255)
}

/// White, the figures' background.
pub(super) const WHITE: ColorU8 = rgb(255, 255, 255);
/// Near black, for frames and text.
pub(super) const INK: ColorU8 = rgb(20, 20, 20);
/// Light grey, for grid lines.
pub(super) const GRID: ColorU8 = rgb(225, 225, 225);

/// Width in image pixels of `text` drawn at `scale`.
pub(super) fn text_width(text: &str, scale: u32) -> f32 {
    text.chars().count() as f32 * (GLYPH * scale) as f32
}

/// Height in image pixels of a line of text drawn at `scale`.
pub(super) fn text_height(scale: u32) -> f32 {
    (GLYPH * scale) as f32
}

/// `text` cut to at most `max_width` pixels at `scale`, with `..` marking a cut.
pub(super) fn fit_text(text: &str, scale: u32, max_width: f32) -> String {
    let max_chars = (max_width / (GLYPH * scale) as f32).floor().max(0.0) as usize;
    if text.chars().count() <= max_chars {
        return text.to_owned();
    }
    let kept: String = text.chars().take(max_chars.saturating_sub(2)).collect();
    format!("{kept}..")
}

/// The glyph rows of `c`, each byte a row whose least significant bit is the
/// leftmost pixel; characters the font lacks are drawn as `?`.
fn glyph(c: char) -> [u8; 8] {
    BASIC_FONTS
        .get(c)
        .or_else(|| LATIN_FONTS.get(c))
        .or_else(|| GREEK_FONTS.get(c))
        .or_else(|| BASIC_FONTS.get('?'))
        .unwrap_or_default()
}

/// The image being drawn, as pixels and as SVG.
pub(super) struct Canvas {
    pixmap: Pixmap,
    svg: Svg,
}

impl Canvas {
    /// A white canvas, or `None` when the size is zero or above [`MAX_PIXELS`].
    pub(super) fn new(width: u32, height: u32) -> Option<Self> {
        if u64::from(width) * u64::from(height) > MAX_PIXELS {
            return None;
        }
        let mut pixmap = Pixmap::new(width, height)?;
        pixmap.fill(Color::WHITE);
        Some(Self {
            pixmap,
            svg: Svg::new(width, height),
        })
    }

    /// The finished image and its SVG document.
    pub(super) fn finish(self) -> (Pixmap, String) {
        (self.pixmap, self.svg.finish())
    }

    /// Fills the rectangle with corner `(x, y)` and the given size; an empty
    /// or non-finite rectangle draws nothing.
    pub(super) fn fill_rect(&mut self, x: f32, y: f32, width: f32, height: f32, color: ColorU8) {
        if self.fill_pixels(x, y, width, height, color) {
            self.svg.rect(x, y, width, height, color);
        }
    }

    /// Fills the rectangle in the pixmap alone (a pixel of a glyph, which
    /// the SVG draws as text); whether it was drawn.
    fn fill_pixels(&mut self, x: f32, y: f32, width: f32, height: f32, color: ColorU8) -> bool {
        let Some(rect) = Rect::from_xywh(x, y, width, height) else {
            return false;
        };
        self.pixmap
            .fill_rect(rect, &solid(color), Transform::identity(), None);
        true
    }

    /// Strokes the open poly-line through `points`, dashed when `dash` gives
    /// the lengths of a dash and of a gap.
    pub(super) fn polyline(
        &mut self,
        points: &[(f32, f32)],
        color: ColorU8,
        width: f32,
        dash: Option<(f32, f32)>,
    ) {
        let mut builder = PathBuilder::new();
        let mut iter = points.iter();
        let Some(&(x0, y0)) = iter.next() else {
            return;
        };
        builder.move_to(x0, y0);
        for &(x, y) in iter {
            builder.line_to(x, y);
        }
        let Some(path) = builder.finish() else {
            return;
        };
        self.svg.polyline(points, color, width, dash);
        let stroke = Stroke {
            width,
            line_cap: LineCap::Butt,
            line_join: LineJoin::Round,
            dash: dash.and_then(|(on, off)| StrokeDash::new(vec![on, off], 0.0)),
            ..Stroke::default()
        };
        self.pixmap
            .stroke_path(&path, &solid(color), &stroke, Transform::identity(), None);
    }

    /// Strokes the outline of a rectangle with a one-pixel line.
    pub(super) fn frame(&mut self, x: f32, y: f32, width: f32, height: f32, color: ColorU8) {
        let (right, bottom) = (x + width, y + height);
        self.polyline(
            &[(x, y), (right, y), (right, bottom), (x, bottom), (x, y)],
            color,
            1.0,
            None,
        );
    }

    /// Fills a marker of the given shape centred on `(x, y)`, `size` pixels across.
    pub(super) fn marker(&mut self, shape: Marker, x: f32, y: f32, size: f32, color: ColorU8) {
        let r = size / 2.0;
        let corners: &[(f32, f32)] = match shape {
            Marker::Circle => &[],
            Marker::Square => {
                let h = r * 0.85;
                &[
                    (x - h, y - h),
                    (x + h, y - h),
                    (x + h, y + h),
                    (x - h, y + h),
                ]
            }
            Marker::Triangle => &[(x, y - r * 1.1), (x + r, y + r * 0.8), (x - r, y + r * 0.8)],
            Marker::Diamond => &[(x, y - r * 1.2), (x + r, y), (x, y + r * 1.2), (x - r, y)],
        };
        let path = if corners.is_empty() {
            self.svg.circle(x, y, r, color);
            PathBuilder::from_circle(x, y, r)
        } else {
            self.svg.polygon(corners, color);
            polygon(corners)
        };
        if let Some(path) = path {
            self.pixmap.fill_path(
                &path,
                &solid(color),
                FillRule::Winding,
                Transform::identity(),
                None,
            );
        }
    }

    /// Draws `text` horizontally at `scale` with its top at `y` and its
    /// `align` point at `x`.
    pub(super) fn text(
        &mut self,
        text: &str,
        x: f32,
        y: f32,
        scale: u32,
        color: ColorU8,
        align: Align,
    ) {
        let left = (x - offset(text, scale, align)).round();
        let top = y.round();
        let box_size = (text_width(text, scale), text_height(scale));
        self.svg.text(text, (left, top), box_size, color, false);
        self.glyph_runs(text, scale, |canvas, run_x, run_y, run_w, size| {
            canvas.fill_pixels(left + run_x, top + run_y, run_w, size, color);
        });
    }

    /// Draws `text` rotated a quarter turn anticlockwise (reading upwards),
    /// with the top of its glyphs at `x` and its `align` point at height `y`.
    pub(super) fn text_up(
        &mut self,
        text: &str,
        x: f32,
        y: f32,
        scale: u32,
        color: ColorU8,
        align: Align,
    ) {
        let bottom = (y + offset(text, scale, align)).round();
        let left = x.round();
        let box_size = (text_width(text, scale), text_height(scale));
        self.svg.text(text, (left, bottom), box_size, color, true);
        self.glyph_runs(text, scale, |canvas, run_x, run_y, run_w, size| {
            canvas.fill_pixels(left + run_y, bottom - run_x - run_w, size, run_w, color);
        });
    }

    /// Calls `draw(self, x, y, width, height)` for each horizontal run of lit
    /// font pixels of `text` laid out from the origin at `scale`.
    fn glyph_runs(
        &mut self,
        text: &str,
        scale: u32,
        mut draw: impl FnMut(&mut Self, f32, f32, f32, f32),
    ) {
        let size = scale as f32;
        for (index, c) in text.chars().enumerate() {
            let origin = index as f32 * (GLYPH * scale) as f32;
            for (row, bits) in glyph(c).into_iter().enumerate() {
                let mut column = 0;
                while column < GLYPH {
                    if bits >> column & 1 == 0 {
                        column += 1;
                        continue;
                    }
                    let start = column;
                    while column < GLYPH && bits >> column & 1 == 1 {
                        column += 1;
                    }
                    let run_x = origin + (start * scale) as f32;
                    let run_w = ((column - start) * scale) as f32;
                    draw(self, run_x, row as f32 * size, run_w, size);
                }
            }
        }
    }
}

/// How far the start of `text` lies before its `align` point.
fn offset(text: &str, scale: u32, align: Align) -> f32 {
    match align {
        Align::Start => 0.0,
        Align::Middle => text_width(text, scale) / 2.0,
        Align::End => text_width(text, scale),
    }
}

/// A closed polygon through `corners`.
fn polygon(corners: &[(f32, f32)]) -> Option<tiny_skia::Path> {
    let mut builder = PathBuilder::new();
    let (&(x0, y0), rest) = corners.split_first()?;
    builder.move_to(x0, y0);
    for &(x, y) in rest {
        builder.line_to(x, y);
    }
    builder.close();
    builder.finish()
}

/// An anti-aliased paint of one colour.
fn solid(color: ColorU8) -> Paint<'static> {
    let mut paint = Paint::default();
    paint.set_color_rgba8(color.red(), color.green(), color.blue(), color.alpha());
    paint
}
