//! Stability heat maps: one panel per integrator over (timestep, stiffness scale).

use std::path::Path;

use tiny_skia::ColorU8;

pub(super) mod cells;
mod legend;

use super::axis::LogAxis;
use super::canvas::{self, Align, Canvas, INK, TEXT, TITLE, WHITE, rgb};
use super::{PlotError, save};
pub use cells::GAIN_FLOOR;
use cells::{Shade, check_panel, edges};
use legend::{LEGEND_LINE, draw_legend, legend_lines};

/// One cell of a stability map: the outcome of one run at one (dt, scale).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    /// Whether the run stayed bounded (as the caller judged it).
    pub stable: bool,
    /// The largest energy ratio seen during the run, `1 + G/(E(0) + max W)`
    /// with the energy gain `G = E − E(0) − W` over the initial energy and
    /// the work done on the system (see `hooke_lab::EnergyBudget`): one for
    /// the exact motion, below one where energy was dissipated.
    pub max_energy_ratio: f64,
}

/// The stability map of one integrator.
#[derive(Clone, Debug, PartialEq)]
pub struct HeatMapPanel {
    /// The panel's title, the integrator's name.
    pub title: String,
    /// Timesteps in seconds, positive, finite and strictly increasing: the columns.
    pub dts: Vec<f64>,
    /// Stiffness scales, positive, finite and strictly increasing: the rows.
    pub scales: Vec<f64>,
    /// `scales.len() × dts.len()` cells, row-major: the cell of `scales[i]`
    /// and `dts[j]` is `cells[i * dts.len() + j]`.
    pub cells: Vec<Cell>,
}

/// A figure of stability maps, one panel per integrator.
#[derive(Clone, Debug, PartialEq)]
pub struct HeatMaps {
    /// The figure's title.
    pub title: String,
    /// The panels, laid out in rows of [`HEAT_MAP_COLUMNS`].
    pub panels: Vec<HeatMapPanel>,
    /// The highest angular frequency ω_max of the scene at stiffness scale 1,
    /// in rad/s, from which each panel draws the line h·ω_max(s) = 2 with
    /// ω_max(s) = ω_max·√s. `None`, or a value that is not finite and
    /// positive, draws no line.
    pub omega_max: Option<f64>,
}

/// Panels in a row of a heat-map figure.
pub const HEAT_MAP_COLUMNS: usize = 4;

/// Width of a panel's block: y-axis title, tick labels, plot area and gap.
const BLOCK_W: u32 = 470;
/// Height of a panel's block: title, plot area, tick labels, x-axis title and gap.
const BLOCK_H: u32 = 400;
/// Plot area of a panel, relative to its block.
const PLOT_X: f32 = 120.0;
const PLOT_Y: f32 = 40.0;
const PLOT_W: f32 = 320.0;
const PLOT_H: f32 = 280.0;
/// Outer margin of the figure, the band for its title and the legend band's
/// height besides its lines.
const MARGIN: u32 = 20;
const TITLE_BAND: u32 = 60;
const LEGEND_BASE: u32 = 40;
/// Least width inside the margins, so that each legend entry fits on a line.
const MIN_WIDTH: u32 = 720;

/// The theoretical line and its halo.
pub(super) const LINE: ColorU8 = rgb(0, 0, 0);
const LINE_WIDTH: f32 = 3.0;
const HALO_WIDTH: f32 = 7.0;

/// Size in pixels of the figure of `maps`: [`HEAT_MAP_COLUMNS`] (or fewer)
/// panels of 470 × 400 pixels a row, centred in a width of at least 720
/// pixels, a 20-pixel margin on each side, a 60-pixel title band, and a
/// legend band of 40 pixels plus 28 for each line its entries need at that
/// width (one line for four columns).
pub fn heat_maps_size(maps: &HeatMaps) -> (u32, u32) {
    let rows = rows_of(maps);
    let width = 2 * MARGIN + grid_width(maps).max(MIN_WIDTH);
    let lines = legend_lines(limit_omega(maps), Shade::of(maps), legend_width(width));
    let lines = u32::try_from(lines).unwrap_or(u32::MAX);
    let legend = LEGEND_BASE.saturating_add(lines.saturating_mul(LEGEND_LINE as u32));
    let height = rows
        .saturating_mul(BLOCK_H)
        .saturating_add(TITLE_BAND + legend);
    (width, height)
}

/// Width of the panels of a row.
fn grid_width(maps: &HeatMaps) -> u32 {
    maps.panels.len().clamp(1, HEAT_MAP_COLUMNS) as u32 * BLOCK_W
}

/// Width available to the legend in a figure `figure_width` pixels wide.
fn legend_width(figure_width: u32) -> f32 {
    figure_width.saturating_sub(2 * MARGIN) as f32 - 20.0
}

/// Rows of panels in the figure of `maps`.
fn rows_of(maps: &HeatMaps) -> u32 {
    u32::try_from(maps.panels.len().div_ceil(HEAT_MAP_COLUMNS).max(1)).unwrap_or(u32::MAX)
}

/// The ω_max of the line, when there is one to draw.
fn limit_omega(maps: &HeatMaps) -> Option<f64> {
    maps.omega_max.filter(|w| w.is_finite() && *w > 0.0)
}

/// The plot area `(x, y, width, height)` of panel `index` in the figure of `maps`.
pub(super) fn plot_area(maps: &HeatMaps, index: usize) -> (f32, f32, f32, f32) {
    let column = (index % HEAT_MAP_COLUMNS) as f32;
    let row = (index / HEAT_MAP_COLUMNS) as f32;
    let indent = (MIN_WIDTH.saturating_sub(grid_width(maps)) / 2) as f32;
    let x = MARGIN as f32 + indent + column * BLOCK_W as f32 + PLOT_X;
    let y = TITLE_BAND as f32 + row * BLOCK_H as f32 + PLOT_Y;
    (x, y, PLOT_W, PLOT_H)
}

/// Writes `maps` to `path` as a PNG of [`heat_maps_size`].
///
/// Each panel's cells span, in log scale, from half-way to the previous grid
/// value to half-way to the next (a lone value gets a decade). Stable cells
/// are blue, darker as the log10 of the energy gain `max_energy_ratio − 1`
/// grows from that of [`GAIN_FLOOR`] (any smaller gain, or a loss, is drawn
/// lightest) to the largest gain among the figure's stable cells, so that
/// a gain of 10⁻⁵ of the allowance shows beside one of 10; unstable cells
/// and cells whose ratio is not finite are red. A panel with no
/// cells, or a figure with no panels, is drawn with a "no data" note.
///
/// # Errors
///
/// [`PlotError::Grid`] when a panel's grid is malformed (values not positive,
/// finite and strictly increasing, or a cell count other than
/// `scales.len() × dts.len()`); [`PlotError::Io`] or [`PlotError::Encode`]
/// when the file cannot be written.
pub fn write_heat_maps(maps: &HeatMaps, path: &Path) -> Result<(), PlotError> {
    for (index, panel) in maps.panels.iter().enumerate() {
        check_panel(panel).map_err(|source| PlotError::Grid {
            path: path.to_owned(),
            index,
            title: panel.title.clone(),
            source,
        })?;
    }
    let (width, height) = heat_maps_size(maps);
    let mut canvas = Canvas::new(width, height).ok_or_else(|| PlotError::Size {
        path: path.to_owned(),
        width,
        height,
    })?;
    let width_f = width as f32;
    let title = canvas::fit_text(&maps.title, TITLE, width_f - 2.0 * MARGIN as f32);
    canvas.text(&title, width_f / 2.0, 20.0, TITLE, INK, Align::Middle);

    let omega = limit_omega(maps);
    let shade = Shade::of(maps);
    for (index, panel) in maps.panels.iter().enumerate() {
        draw_panel(&mut canvas, panel, plot_area(maps, index), omega, shade);
    }
    if maps.panels.is_empty() {
        let (x, y, w, h) = plot_area(maps, 0);
        canvas.frame(x, y, w, h, INK);
        no_data(&mut canvas, (x, y, w, h));
    }
    let legend_top = TITLE_BAND as f32 + BLOCK_H.saturating_mul(rows_of(maps)) as f32;
    let corner = (MARGIN as f32 + 10.0, legend_top + 20.0);
    draw_legend(&mut canvas, corner, legend_width(width), omega, shade);
    save(canvas, path)
}

/// Draws one panel in the plot area `(x, y, w, h)`.
fn draw_panel(
    canvas: &mut Canvas,
    panel: &HeatMapPanel,
    (x, y, w, h): (f32, f32, f32, f32),
    omega: Option<f64>,
    shade: Shade,
) {
    let title = canvas::fit_text(&panel.title, TEXT, w);
    canvas.text(&title, x + w / 2.0, y - 30.0, TEXT, INK, Align::Middle);
    let x_edges = edges(&panel.dts);
    let y_edges = edges(&panel.scales);
    let (Some(&x_lo), Some(&x_hi), Some(&y_lo), Some(&y_hi)) = (
        x_edges.first(),
        x_edges.last(),
        y_edges.first(),
        y_edges.last(),
    ) else {
        canvas.frame(x, y, w, h, INK);
        no_data(canvas, (x, y, w, h));
        return;
    };
    let x_axis = LogAxis::new(x_lo, x_hi, x, x + w);
    let y_axis = LogAxis::new(y_lo, y_hi, y + h, y);
    let x_px: Vec<f32> = x_edges
        .iter()
        .map(|&e| x_axis.pixel_of_log(e).round())
        .collect();
    let y_px: Vec<f32> = y_edges
        .iter()
        .map(|&e| y_axis.pixel_of_log(e).round())
        .collect();
    for (row, rows) in y_px.windows(2).enumerate() {
        for (column, columns) in x_px.windows(2).enumerate() {
            let Some(&cell) = panel.cells.get(row * panel.dts.len() + column) else {
                continue;
            };
            let (left, cell_w) = (columns[0], columns[1] - columns[0]);
            let (top, cell_h) = (rows[1], rows[0] - rows[1]);
            let gap_x = if cell_w >= 6.0 { 1.0 } else { 0.0 };
            let gap_y = if cell_h >= 6.0 { 1.0 } else { 0.0 };
            canvas.fill_rect(left, top, cell_w - gap_x, cell_h - gap_y, shade.color(cell));
        }
    }
    if let Some(omega) = omega {
        draw_limit(canvas, x_axis, y_axis, omega);
    }
    canvas.frame(x, y, w, h, INK);
    super::draw_axes(canvas, (x, y, w, h), x_axis, y_axis, false);
    canvas.text(
        "dt (s)",
        x + w / 2.0,
        y + h + 36.0,
        TEXT,
        INK,
        Align::Middle,
    );
    canvas.text_up(
        "stiffness scale",
        x - 114.0,
        y + h / 2.0,
        TEXT,
        INK,
        Align::Middle,
    );
}

/// Draws the line h·ω_max·√s = 2, that is log10(dt) = log10(2/ω_max) − log10(s)/2,
/// where it crosses the panel.
fn draw_limit(canvas: &mut Canvas, x_axis: LogAxis, y_axis: LogAxis, omega: f64) {
    let c = (2.0 / omega).log10();
    let s_lo = y_axis.lo().max(2.0 * (c - x_axis.hi()));
    let s_hi = y_axis.hi().min(2.0 * (c - x_axis.lo()));
    if s_hi <= s_lo {
        return;
    }
    let ends = [s_lo, s_hi].map(|s| (x_axis.pixel_of_log(c - s / 2.0), y_axis.pixel_of_log(s)));
    canvas.polyline(&ends, WHITE, HALO_WIDTH, None);
    canvas.polyline(&ends, LINE, LINE_WIDTH, None);
}

/// Writes "no data" in the middle of a plot area.
fn no_data(canvas: &mut Canvas, (x, y, w, h): (f32, f32, f32, f32)) {
    canvas.text(
        "no data",
        x + w / 2.0,
        y + h / 2.0 - 8.0,
        TEXT,
        INK,
        Align::Middle,
    );
}
