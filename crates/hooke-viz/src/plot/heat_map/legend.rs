//! The legend of a heat-map figure: the stable shades, the unstable colour
//! and the theoretical line, laid out in as many lines as the width needs.

use crate::plot::canvas::{self, Align, Canvas, INK, TEXT};

use super::cells::{GAIN_FLOOR, Shade, UNSTABLE, blend};
use super::{LINE, LINE_WIDTH};

/// The key drawn before a legend entry's text.
#[derive(Clone, Copy)]
enum Key {
    /// The ramp of stable shades.
    Ramp,
    /// A square of the unstable colour.
    Unstable,
    /// A piece of the theoretical line.
    Limit,
}

impl Key {
    /// Width of the key and the space after it.
    fn width(self) -> f32 {
        match self {
            Key::Ramp => 130.0,
            Key::Unstable => 34.0,
            Key::Limit => 50.0,
        }
    }
}

/// Space between legend entries and the height of a legend line.
const ENTRY_GAP: f32 = 40.0;
pub(super) const LEGEND_LINE: f32 = 28.0;

/// The legend's entries.
fn legend_entries(omega: Option<f64>, shade: Shade) -> Vec<(Key, String)> {
    let floor = crate::plot::format_value(GAIN_FLOOR);
    let top = crate::plot::format_value(10f64.powf(shade.top_log));
    let mut entries = vec![
        (
            Key::Ramp,
            format!("stable, gain {floor} to {top} × E(0)+max W"),
        ),
        (Key::Unstable, "unstable or non-finite".to_owned()),
    ];
    if let Some(omega) = omega {
        let omega = crate::plot::format_value(omega);
        entries.push((Key::Limit, format!("h·ω = 2, ω = {omega}·scale^½ rad/s")));
    }
    entries
}

/// The legend's entries placed in lines no wider than `width`: for each
/// entry, its line and its offset from the left.
fn legend_layout(entries: &[(Key, String)], width: f32) -> Vec<(usize, f32)> {
    let mut line = 0;
    let mut x = 0.0;
    let mut placed = Vec::with_capacity(entries.len());
    for (key, text) in entries {
        let entry_w = key.width() + canvas::text_width(text, TEXT);
        if x > 0.0 && x + entry_w > width {
            line += 1;
            x = 0.0;
        }
        placed.push((line, x));
        x += entry_w + ENTRY_GAP;
    }
    placed
}

/// Lines the legend takes in a band `width` pixels wide.
pub(super) fn legend_lines(omega: Option<f64>, shade: Shade, width: f32) -> usize {
    let entries = legend_entries(omega, shade);
    legend_layout(&entries, width)
        .last()
        .map_or(1, |&(line, _)| line + 1)
}

/// Draws the legend in a band `width` pixels wide whose top-left corner is `(left, top)`.
pub(super) fn draw_legend(
    canvas: &mut Canvas,
    (left, top): (f32, f32),
    width: f32,
    omega: Option<f64>,
    shade: Shade,
) {
    let entries = legend_entries(omega, shade);
    let layout = legend_layout(&entries, width);
    for ((key, text), (line, offset)) in entries.iter().zip(layout) {
        let x = left + offset;
        let row = top + line as f32 * LEGEND_LINE;
        match key {
            Key::Ramp => {
                let ramp_w = 120;
                for i in 0..ramp_w {
                    let t = i as f32 / (ramp_w - 1) as f32;
                    canvas.fill_rect(x + i as f32, row, 1.0, 16.0, blend(t));
                }
            }
            Key::Unstable => canvas.fill_rect(x, row, 24.0, 16.0, UNSTABLE),
            Key::Limit => {
                let ends = [(x, row + 8.0), (x + 40.0, row + 8.0)];
                canvas.polyline(&ends, LINE, LINE_WIDTH, None);
            }
        }
        let text = canvas::fit_text(text, TEXT, width - key.width());
        canvas.text(&text, x + key.width(), row, TEXT, INK, Align::Start);
    }
}
