//! The cell grid of a panel: its checks, its cell edges and its colours.

use tiny_skia::ColorU8;

use crate::plot::GridError;
use crate::plot::canvas::rgb;

use super::{Cell, HeatMapPanel, HeatMaps};

/// Unstable (or non-finite) cells.
pub(in crate::plot) const UNSTABLE: ColorU8 = rgb(215, 48, 39);
/// Stable cells, from no energy gain to the largest.
const STABLE_LIGHT: [f32; 3] = [222.0, 235.0, 247.0];
const STABLE_DARK: [f32; 3] = [33.0, 102.0, 172.0];
/// Checks that the panel's grid can be drawn.
pub(super) fn check_panel(panel: &HeatMapPanel) -> Result<(), GridError> {
    check_axis("dts", &panel.dts)?;
    check_axis("scales", &panel.scales)?;
    let expected = panel.dts.len() * panel.scales.len();
    if panel.cells.len() == expected {
        Ok(())
    } else {
        Err(GridError::CellCount {
            expected,
            found: panel.cells.len(),
        })
    }
}

/// Checks that grid values are positive, finite and strictly increasing.
fn check_axis(axis: &'static str, values: &[f64]) -> Result<(), GridError> {
    if let Some(index) = values.iter().position(|v| !(v.is_finite() && *v > 0.0)) {
        return Err(GridError::NotPositive {
            axis,
            index,
            value: values[index],
        });
    }
    if let Some(index) = values.windows(2).position(|w| w[1] <= w[0]) {
        return Err(GridError::NotIncreasing {
            axis,
            index: index + 1,
        });
    }
    Ok(())
}

/// The energy gain, as a fraction of the allowance (`max_energy_ratio −
/// 1`), up to which a stable cell is drawn in the lightest shade: below
/// it lie the exact motion's zero and the rounding of long runs.
pub const GAIN_FLOOR: f64 = 1e-9;

/// The colour scale of stable cells: the shade darkens with the log of the
/// energy gain `max_energy_ratio − 1` from [`GAIN_FLOOR`] to the largest
/// gain among the figure's stable cells.
#[derive(Clone, Copy)]
pub(super) struct Shade {
    /// The log10 of the gain drawn darkest (at least that of [`GAIN_FLOOR`]).
    pub(super) top_log: f64,
}

impl Shade {
    /// The colour scale of the stable cells of `maps`.
    pub(super) fn of(maps: &HeatMaps) -> Self {
        let top_log = maps
            .panels
            .iter()
            .flat_map(|p| p.cells.iter())
            .filter(|c| c.stable)
            .filter_map(|c| gain_log(c.max_energy_ratio))
            .fold(GAIN_FLOOR.log10(), f64::max);
        Shade { top_log }
    }

    /// The colour of a cell.
    pub(super) fn color(self, cell: Cell) -> ColorU8 {
        if !cell.stable || !cell.max_energy_ratio.is_finite() {
            return UNSTABLE;
        }
        let floor = GAIN_FLOOR.log10();
        let t = match gain_log(cell.max_energy_ratio) {
            Some(log) if self.top_log > floor => {
                ((log - floor) / (self.top_log - floor)).clamp(0.0, 1.0)
            }
            _ => 0.0,
        };
        blend(t as f32)
    }
}

/// The log10 of the energy gain `ratio − 1` of a cell, when it is finite
/// and above [`GAIN_FLOOR`].
fn gain_log(ratio: f64) -> Option<f64> {
    let gain = ratio - 1.0;
    (gain.is_finite() && gain > GAIN_FLOOR).then(|| gain.log10())
}

/// The stable colour a fraction `t` of the way from light to dark.
pub(in crate::plot) fn blend(t: f32) -> ColorU8 {
    let channel =
        |i: usize| (STABLE_LIGHT[i] + t * (STABLE_DARK[i] - STABLE_LIGHT[i])).round() as u8;
    rgb(channel(0), channel(1), channel(2))
}

/// Cell edges in log10 for grid `values`: half-way between neighbours,
/// mirrored at the ends; a lone value gets half a decade each side.
pub(in crate::plot) fn edges(values: &[f64]) -> Vec<f64> {
    let logs: Vec<f64> = values.iter().map(|v| v.log10()).collect();
    match logs.as_slice() {
        [] => Vec::new(),
        [only] => vec![only - 0.5, only + 0.5],
        [first, second, ..] => {
            let (last, before_last) = (logs[logs.len() - 1], logs[logs.len() - 2]);
            let mut edges = Vec::with_capacity(logs.len() + 1);
            edges.push(first - (second - first) / 2.0);
            edges.extend(logs.windows(2).map(|w| (w[0] + w[1]) / 2.0));
            edges.push(last + (last - before_last) / 2.0);
            edges
        }
    }
}
