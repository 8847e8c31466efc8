//! Log-log line plots: one line with markers per integrator.

use std::path::Path;

use tiny_skia::ColorU8;

use super::axis::LogAxis;
use super::canvas::{self, Align, Canvas, INK, Marker, TEXT, TITLE, rgb};
use super::{PlotError, save};

/// One line of a plot: an integrator's measurements.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// The name shown in the legend.
    pub label: String,
    /// The points `(x, y)`, joined in this order. Points with a coordinate
    /// that is not finite and positive are skipped.
    pub points: Vec<(f64, f64)>,
}

/// A horizontal dashed reference line, such as an error tolerance, named in the legend.
#[derive(Clone, Debug, PartialEq)]
pub struct Reference {
    /// Its height in y units; a value that is not finite and positive draws nothing.
    pub y: f64,
    /// Its legend entry, such as `1 mm`.
    pub label: String,
}

/// A plot of series on logarithmic axes.
#[derive(Clone, Debug, PartialEq)]
pub struct LogLogPlot {
    /// The plot's title.
    pub title: String,
    /// The x-axis title, with its unit.
    pub x_label: String,
    /// The y-axis title, with its unit.
    pub y_label: String,
    /// The lines, coloured and marked in order.
    pub series: Vec<Series>,
    /// An optional horizontal reference line.
    pub reference: Option<Reference>,
}

/// Width of a log-log figure, in pixels.
pub const LOG_LOG_WIDTH: u32 = 1200;
/// Height of a log-log figure, in pixels.
pub const LOG_LOG_HEIGHT: u32 = 900;

/// Series colours, repeated (with other markers) past the tenth series.
pub(super) const PALETTE: [ColorU8; 10] = [
    rgb(31, 100, 180),
    rgb(240, 120, 20),
    rgb(40, 150, 50),
    rgb(200, 30, 40),
    rgb(130, 90, 180),
    rgb(140, 80, 60),
    rgb(220, 100, 180),
    rgb(100, 100, 100),
    rgb(170, 170, 20),
    rgb(20, 180, 200),
];
/// The reference line: grey, 12-pixel dashes and 8-pixel gaps.
const REFERENCE: ColorU8 = rgb(90, 90, 90);
const REFERENCE_DASH: (f32, f32) = (12.0, 8.0);

/// Plot-area margins: left (y labels and title), top (title), bottom (x labels and title).
const LEFT: f32 = 130.0;
const TOP: f32 = 70.0;
const BOTTOM: f32 = 100.0;
/// Space right of the legend, and the legend's key width.
const RIGHT: f32 = 30.0;
const KEY: f32 = 50.0;
/// Longest legend label shown, in characters, and the height of a legend row.
const LABEL_CHARS: usize = 24;
const LEGEND_ROW: f32 = 28.0;
const MARKER: f32 = 10.0;

/// The plot area `(x, y, width, height)` of `plot`: the legend takes the
/// right-hand side, as wide as its longest label (cut at 24 characters).
pub(super) fn plot_area(plot: &LogLogPlot) -> (f32, f32, f32, f32) {
    let labels = plot.series.iter().map(|s| &s.label);
    let longest = labels
        .chain(drawn_reference(plot).map(|r| &r.label))
        .map(|label| label.chars().count().min(LABEL_CHARS))
        .max();
    let legend = longest.map_or(0.0, |chars| {
        KEY + canvas::text_width(&"m".repeat(chars), TEXT) + 30.0
    });
    let width = LOG_LOG_WIDTH as f32 - LEFT - RIGHT - legend;
    let height = LOG_LOG_HEIGHT as f32 - TOP - BOTTOM;
    (LEFT, TOP, width, height)
}

/// The axes of `plot` over its plot area: each spans its valid values (and
/// the reference line's height) with 5 % of the span to spare each side.
pub(super) fn axes(plot: &LogLogPlot) -> (LogAxis, LogAxis) {
    let (x, y, w, h) = plot_area(plot);
    let points: Vec<(f64, f64)> = valid_points(plot).flatten().collect();
    let reference = plot.reference.as_ref().and_then(|r| valid(r.y));
    let x_axis = LogAxis::fitting(points.iter().map(|p| p.0.log10()), 0.05, x, x + w);
    let y_logs = points.iter().map(|p| p.1).chain(reference).map(f64::log10);
    let y_axis = LogAxis::fitting(y_logs, 0.05, y + h, y);
    (x_axis, y_axis)
}

/// `value` if it can be drawn on a logarithmic axis.
fn valid(value: f64) -> Option<f64> {
    (value.is_finite() && value > 0.0).then_some(value)
}

/// Each series' drawable points.
fn valid_points(plot: &LogLogPlot) -> impl Iterator<Item = impl Iterator<Item = (f64, f64)> + '_> {
    plot.series.iter().map(|s| {
        s.points
            .iter()
            .filter_map(|&(x, y)| Some((valid(x)?, valid(y)?)))
    })
}

/// Writes `plot` to `path` as a PNG of [`LOG_LOG_WIDTH`] × [`LOG_LOG_HEIGHT`].
///
/// Series are drawn in order, each in its own colour and marker, joining its
/// drawable points in order; the legend lies right of the plot area. A plot
/// with no drawable point is still written, its axes spanning 0.1 to 10,
/// with a "no data" note.
///
/// # Errors
///
/// [`PlotError::Io`] or [`PlotError::Encode`] when the file cannot be written.
pub fn write_log_log(plot: &LogLogPlot, path: &Path) -> Result<(), PlotError> {
    let (width, height) = (LOG_LOG_WIDTH, LOG_LOG_HEIGHT);
    let mut canvas = Canvas::new(width, height).ok_or_else(|| PlotError::Size {
        path: path.to_owned(),
        width,
        height,
    })?;
    let area @ (x, y, w, h) = plot_area(plot);
    let title = canvas::fit_text(&plot.title, TITLE, width as f32 - 40.0);
    canvas.text(&title, width as f32 / 2.0, 24.0, TITLE, INK, Align::Middle);
    let (x_axis, y_axis) = axes(plot);
    super::draw_axes(&mut canvas, area, x_axis, y_axis, true);

    if let Some(reference) = drawn_reference(plot) {
        let py = y_axis.pixel(reference.y);
        canvas.polyline(
            &[(x, py), (x + w, py)],
            REFERENCE,
            2.0,
            Some(REFERENCE_DASH),
        );
    }

    let mut any = false;
    for (index, points) in valid_points(plot).enumerate() {
        let (color, marker) = style(index);
        let pixels: Vec<(f32, f32)> = points
            .map(|(px, py)| (x_axis.pixel(px), y_axis.pixel(py)))
            .collect();
        any |= !pixels.is_empty();
        canvas.polyline(&pixels, color, 2.0, None);
        for &(px, py) in &pixels {
            canvas.marker(marker, px, py, MARKER, color);
        }
    }
    if !any {
        canvas.text(
            "no data",
            x + w / 2.0,
            y + h / 2.0 - 8.0,
            TEXT,
            INK,
            Align::Middle,
        );
    }
    canvas.frame(x, y, w, h, INK);

    let x_title = canvas::fit_text(&plot.x_label, TEXT, w);
    canvas.text(
        &x_title,
        x + w / 2.0,
        y + h + 50.0,
        TEXT,
        INK,
        Align::Middle,
    );
    let y_title = canvas::fit_text(&plot.y_label, TEXT, h);
    canvas.text_up(&y_title, 24.0, y + h / 2.0, TEXT, INK, Align::Middle);
    draw_legend(&mut canvas, plot, x + w + 30.0, y + 10.0);
    save(canvas, path)
}

/// Colour and marker of the series at `index`.
pub(super) fn style(index: usize) -> (ColorU8, Marker) {
    let color = PALETTE[index % PALETTE.len()];
    let marker = Marker::ALL[(index + index / PALETTE.len()) % Marker::ALL.len()];
    (color, marker)
}

/// Draws the legend with its top-left corner at `(left, top)`: one row per
/// series, then the reference line when it is drawn.
fn draw_legend(canvas: &mut Canvas, plot: &LogLogPlot, left: f32, top: f32) {
    let max_width = canvas::text_width(&"m".repeat(LABEL_CHARS), TEXT);
    let key = [(left, top + 8.0), (left + 36.0, top + 8.0)];
    let mut row = 0.0;
    for (index, series) in plot.series.iter().enumerate() {
        let (color, marker) = style(index);
        canvas.polyline(&shift(key, row), color, 2.0, None);
        canvas.marker(marker, left + 18.0, top + row + 8.0, MARKER, color);
        let label = canvas::fit_text(&series.label, TEXT, max_width);
        canvas.text(&label, left + KEY, top + row, TEXT, INK, Align::Start);
        row += LEGEND_ROW;
    }
    if let Some(reference) = drawn_reference(plot) {
        canvas.polyline(&shift(key, row), REFERENCE, 2.0, Some(REFERENCE_DASH));
        let label = canvas::fit_text(&reference.label, TEXT, max_width);
        canvas.text(&label, left + KEY, top + row, TEXT, INK, Align::Start);
    }
}

/// The two points of a legend key moved down by `dy`.
fn shift(key: [(f32, f32); 2], dy: f32) -> [(f32, f32); 2] {
    key.map(|(x, y)| (x, y + dy))
}

/// The reference line, when it has a height that can be drawn.
fn drawn_reference(plot: &LogLogPlot) -> Option<&Reference> {
    plot.reference.as_ref().filter(|r| valid(r.y).is_some())
}
