//! Figures of the lab's measurements: stability heat maps
//! ([`write_heat_maps`]) and log-log line plots ([`write_log_log`]) such as
//! error against run time or against timestep, each written as a PNG and,
//! beside it, as an SVG of the same drawing ([`svg_path`]): vector, for
//! papers, with its text as text.
//!
//! The module takes plain data (names, numbers, cells) and knows nothing else
//! of the lab. Figures are drawn with `tiny-skia`, which the workspace already
//! uses for rendering and which writes PNG itself, and text is set in the
//! public-domain 8×8 bitmap font of the `font8x8` crate (no dependencies of
//! its own), each font pixel drawn as a 2 × 2 square (3 × 3 for titles). No
//! system font is looked up, so figures come out the same on a machine with
//! no fonts installed. The font covers ASCII, Latin-1 and Greek; other
//! characters are drawn as `?`. The SVG sets the same text in the viewer's
//! monospace font, stretched to the bitmap text's width.
//!
//! A plotting crate was measured instead of this module: `plotters` 0.3
//! with its default features pulls in 46 crates, among them `font-kit`,
//! `freetype-sys` and `yeslogic-fontconfig-sys`, which build C code and
//! look fonts up on the system; reduced to its SVG and bitmap backends with
//! an embedded-font renderer (`ab_glyph`) it still adds 26 (`image` 0.24,
//! `jpeg-decoder`, `ttf-parser`, a second `png`), needs a TrueType font
//! shipped with the crate, and would not replace `tiny-skia`, which the
//! frame renderer uses. Recording each drawing call of this module as an
//! SVG element costs about 150 lines and no dependency, and the PNG and SVG
//! of a figure cannot disagree.
//!
//! Axes are logarithmic, ticked at powers of ten and labelled `1e-3`,
//! `1e-2`, ... (every second or fifth decade when labels would overlap; at
//! 1, 2 and 5 times powers of ten when an axis spans less than two decades).
//!
//! Values that cannot be drawn never make a writer panic: points with a
//! coordinate that is not finite and positive are skipped, a plot with
//! nothing to draw gets a "no data" note, and only a malformed heat-map grid
//! is an error.

mod axis;
mod canvas;
mod heat_map;
mod log_log;
mod svg;
#[cfg(test)]
mod tests;

use std::path::{Path, PathBuf};

use thiserror::Error;

pub use heat_map::{
    Cell, GAIN_FLOOR, HEAT_MAP_COLUMNS, HeatMapPanel, HeatMaps, heat_maps_size, write_heat_maps,
};
pub use log_log::{LOG_LOG_HEIGHT, LOG_LOG_WIDTH, LogLogPlot, Reference, Series, write_log_log};

use axis::LogAxis;
use canvas::{Align, Canvas, GRID, INK, TEXT};

/// A figure that could not be drawn or written; each variant names the file.
#[derive(Debug, Error)]
pub enum PlotError {
    /// The file could not be written (missing directory, no permission, disk full, ...).
    #[error("cannot write {}: {source}", path.display())]
    Io {
        /// The figure's file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The image could not be encoded as PNG.
    #[error("cannot encode {} as PNG: {message}", path.display())]
    Encode {
        /// The figure's file.
        path: PathBuf,
        /// What the encoder said.
        message: String,
    },
    /// The figure would be an image of more than 64 Mi pixels (heat maps
    /// of some 300 panels or more).
    #[error("cannot draw {}: a {width} × {height} pixel image is too large", path.display())]
    Size {
        /// The figure's file.
        path: PathBuf,
        /// Width in pixels.
        width: u32,
        /// Height in pixels.
        height: u32,
    },
    /// A heat-map panel's grid is malformed.
    #[error("cannot draw {}: panel {index} ({title}): {source}", path.display())]
    Grid {
        /// The figure's file.
        path: PathBuf,
        /// Index of the panel in [`HeatMaps::panels`].
        index: usize,
        /// The panel's title.
        title: String,
        /// What is wrong with the grid.
        source: GridError,
    },
}

/// What is wrong with a heat-map panel's grid.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum GridError {
    /// A grid value is not finite and positive, so has no place on a log axis.
    #[error("{axis}[{index}] = {value} is not a finite positive number")]
    NotPositive {
        /// `dts` or `scales`.
        axis: &'static str,
        /// Index of the value.
        index: usize,
        /// The value.
        value: f64,
    },
    /// Grid values do not increase strictly.
    #[error("{axis}[{index}] is not greater than the value before it")]
    NotIncreasing {
        /// `dts` or `scales`.
        axis: &'static str,
        /// Index of the first value out of order.
        index: usize,
    },
    /// The number of cells is not `scales.len() × dts.len()`.
    #[error("{found} cells for a grid of {expected}")]
    CellCount {
        /// `scales.len() × dts.len()`.
        expected: usize,
        /// `cells.len()`.
        found: usize,
    },
}

/// Encodes the canvas as PNG and writes it to `path`, and its SVG twin to
/// [`svg_path`]`(path)`.
fn save(canvas: Canvas, path: &Path) -> Result<(), PlotError> {
    let (pixmap, svg) = canvas.finish();
    let png = pixmap.encode_png().map_err(|e| PlotError::Encode {
        path: path.to_owned(),
        message: e.to_string(),
    })?;
    let write = |path: PathBuf, bytes: &[u8]| {
        std::fs::write(&path, bytes).map_err(|source| PlotError::Io { path, source })
    };
    write(path.to_owned(), &png)?;
    write(svg_path(path), svg.as_bytes())
}

/// Where a figure written to `path` puts its SVG: the same name with the
/// extension `svg`.
///
/// ```
/// use std::path::Path;
/// let svg = hooke_viz::plot::svg_path(Path::new("out/stability.png"));
/// assert_eq!(svg, Path::new("out/stability.svg"));
/// ```
#[must_use]
pub fn svg_path(path: &Path) -> PathBuf {
    path.with_extension("svg")
}

/// Draws tick marks and labels below and left of the plot area
/// `(x, y, w, h)`, and with `grid` a light line across the area at each tick.
fn draw_axes(
    canvas: &mut Canvas,
    (x, y, w, h): (f32, f32, f32, f32),
    x_axis: LogAxis,
    y_axis: LogAxis,
    grid: bool,
) {
    let bottom = y + h;
    for tick in x_axis.ticks(|label| canvas::text_width(label, TEXT) + 16.0) {
        if grid {
            canvas.polyline(&[(tick.pixel, y), (tick.pixel, bottom)], GRID, 1.0, None);
        }
        let length = if tick.label.is_some() { 8.0 } else { 4.0 };
        canvas.polyline(
            &[(tick.pixel, bottom), (tick.pixel, bottom + length)],
            INK,
            1.0,
            None,
        );
        if let Some(label) = tick.label {
            canvas.text(&label, tick.pixel, bottom + 12.0, TEXT, INK, Align::Middle);
        }
    }
    for tick in y_axis.ticks(|_| canvas::text_height(TEXT) + 12.0) {
        if grid {
            canvas.polyline(&[(x, tick.pixel), (x + w, tick.pixel)], GRID, 1.0, None);
        }
        let length = if tick.label.is_some() { 8.0 } else { 4.0 };
        canvas.polyline(&[(x - length, tick.pixel), (x, tick.pixel)], INK, 1.0, None);
        if let Some(label) = tick.label {
            let top = tick.pixel - canvas::text_height(TEXT) / 2.0;
            canvas.text(&label, x - 12.0, top, TEXT, INK, Align::End);
        }
    }
}

/// `value` with three significant digits, in scientific notation outside
/// 0.01 to 10 000.
fn format_value(value: f64) -> String {
    let magnitude = value.abs();
    if (1e-2..1e4).contains(&magnitude) {
        let digits = (2 - magnitude.log10().floor() as i32).max(0) as usize;
        let text = format!("{value:.digits$}");
        if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').to_owned()
        } else {
            text
        }
    } else {
        format!("{value:.2e}")
    }
}
