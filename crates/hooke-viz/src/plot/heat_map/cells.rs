//! The cell grid of a panel: its checks, its cell edges and its colours.

use tiny_skia::ColorU8;

use crate::plot::GridError;
use crate::plot::canvas::rgb;

use super::{Cell, HeatMapPanel, HeatMaps};

/// Unstable (or non-finite) cells.
pub(in crate::plot) const UNSTABLE: ColorU8 = rgb(215, 48, 39);
/// Stable cells, from the smallest energy growth to the largest.
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

/// The colour scale of stable cells.
#[derive(Clone, Copy)]
pub(super) struct Shade {
    /// The log10(max_energy_ratio) drawn darkest.
    pub(super) top_log: f64,
}

impl Shade {
    /// The colour scale of the stable cells of `maps`.
    pub(super) fn of(maps: &HeatMaps) -> Self {
        let top_log = maps
            .panels
            .iter()
            .flat_map(|p| p.cells.iter())
            .filter(|c| c.stable && c.max_energy_ratio.is_finite())
            .map(|c| c.max_energy_ratio.log10().max(0.0))
            .fold(0.0, f64::max);
        Shade { top_log }
    }

    /// The colour of a cell.
    pub(super) fn color(self, cell: Cell) -> ColorU8 {
        if !cell.stable || !cell.max_energy_ratio.is_finite() {
            return UNSTABLE;
        }
        let t = if self.top_log > 0.0 {
            (cell.max_energy_ratio.log10() / self.top_log).clamp(0.0, 1.0)
        } else {
            0.0
        };
        blend(t as f32)
    }
}

/// The stable colour a fraction `t` of the way from light to dark.
pub(super) fn blend(t: f32) -> ColorU8 {
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
