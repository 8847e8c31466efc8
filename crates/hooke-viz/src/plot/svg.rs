//! [`Svg`]: the vector twin of a figure, one SVG element per drawing call
//! of the [`Canvas`](super::canvas::Canvas) that draws its PNG.

use std::fmt::Write;

use tiny_skia::ColorU8;

/// An SVG document being written, in the canvas's pixel coordinates.
pub(super) struct Svg {
    body: String,
    width: u32,
    height: u32,
}

/// `#rrggbb`.
fn hex(color: ColorU8) -> String {
    format!(
        "#{:02x}{:02x}{:02x}",
        color.red(),
        color.green(),
        color.blue()
    )
}

/// `text` with the characters XML reserves escaped.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

impl Svg {
    /// An empty white document of the given size.
    pub(super) fn new(width: u32, height: u32) -> Self {
        let mut svg = Self {
            body: String::new(),
            width,
            height,
        };
        svg.rect(
            0.0,
            0.0,
            width as f32,
            height as f32,
            ColorU8::from_rgba(255, 255, 255, 255),
        );
        svg
    }

    /// The finished document.
    pub(super) fn finish(self) -> String {
        format!(
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
             <svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
             viewBox=\"0 0 {w} {h}\">\n{body}</svg>\n",
            w = self.width,
            h = self.height,
            body = self.body
        )
    }

    /// A filled rectangle.
    pub(super) fn rect(&mut self, x: f32, y: f32, width: f32, height: f32, color: ColorU8) {
        let _ = writeln!(
            self.body,
            "<rect x=\"{x}\" y=\"{y}\" width=\"{width}\" height=\"{height}\" fill=\"{}\"/>",
            hex(color)
        );
    }

    /// An open poly-line, dashed when `dash` gives a dash and a gap.
    pub(super) fn polyline(
        &mut self,
        points: &[(f32, f32)],
        color: ColorU8,
        width: f32,
        dash: Option<(f32, f32)>,
    ) {
        let points: Vec<String> = points.iter().map(|(x, y)| format!("{x},{y}")).collect();
        let dash = dash.map_or(String::new(), |(on, off)| {
            format!(" stroke-dasharray=\"{on} {off}\"")
        });
        let _ = writeln!(
            self.body,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{width}\" \
             stroke-linejoin=\"round\"{dash}/>",
            points.join(" "),
            hex(color)
        );
    }

    /// A filled circle.
    pub(super) fn circle(&mut self, x: f32, y: f32, r: f32, color: ColorU8) {
        let _ = writeln!(
            self.body,
            "<circle cx=\"{x}\" cy=\"{y}\" r=\"{r}\" fill=\"{}\"/>",
            hex(color)
        );
    }

    /// A filled closed polygon.
    pub(super) fn polygon(&mut self, corners: &[(f32, f32)], color: ColorU8) {
        let points: Vec<String> = corners.iter().map(|(x, y)| format!("{x},{y}")).collect();
        let _ = writeln!(
            self.body,
            "<polygon points=\"{}\" fill=\"{}\"/>",
            points.join(" "),
            hex(color)
        );
    }

    /// `text` in a monospace font `size` pixels high, stretched to `width`
    /// pixels so that it takes the bitmap font's place, with its top-left
    /// corner at `(x, y)`; with `up`, rotated a quarter turn anticlockwise
    /// about that corner, reading upwards from it.
    pub(super) fn text(
        &mut self,
        text: &str,
        (x, y): (f32, f32),
        (width, size): (f32, f32),
        color: ColorU8,
        up: bool,
    ) {
        let rotate = if up {
            format!(" transform=\"rotate(-90 {x} {y})\"")
        } else {
            String::new()
        };
        let _ = writeln!(
            self.body,
            "<text x=\"{x}\" y=\"{baseline}\" font-family=\"monospace\" font-size=\"{size}\" \
             textLength=\"{width}\" lengthAdjust=\"spacingAndGlyphs\" fill=\"{}\"{rotate}>{}</text>",
            hex(color),
            escape(text),
            baseline = y + 0.8 * size,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_document_holds_its_elements_with_text_escaped() {
        let mut svg = Svg::new(40, 30);
        let ink = ColorU8::from_rgba(20, 20, 20, 255);
        svg.polyline(&[(0.0, 1.0), (2.0, 3.0)], ink, 1.5, Some((4.0, 2.0)));
        svg.text("a<b", (1.0, 2.0), (24.0, 16.0), ink, false);
        let document = svg.finish();
        assert!(document.starts_with("<?xml"));
        assert!(document.contains("viewBox=\"0 0 40 30\""));
        assert!(document.contains("points=\"0,1 2,3\""));
        assert!(document.contains("stroke=\"#141414\" stroke-width=\"1.5\""));
        assert!(document.contains("stroke-dasharray=\"4 2\""));
        assert!(document.contains(">a&lt;b</text>"));
        assert!(document.trim_end().ends_with("</svg>"));
    }
}
