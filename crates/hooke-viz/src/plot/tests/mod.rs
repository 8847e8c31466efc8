//! Figures written to a temporary directory and read back pixel by pixel.
//!
//! With `HOOKE_PLOT_SAMPLES=<dir>` set, the sample figures are also copied
//! there for a person to look at.

mod heat_map;
mod log_log;

use std::path::{Path, PathBuf};

use tempfile::TempDir;
use tiny_skia::{ColorU8, Pixmap};

use super::axis::LogAxis;
use super::*;

/// Integrator names of the sample figures.
pub(super) const NAMES: [&str; 6] = [
    "explicit Euler",
    "symplectic Euler",
    "velocity Verlet",
    "RK4",
    "backward Euler",
    "backward Euler + CG",
];

/// `n` values from `10^lo` to `10^hi`, evenly spaced in log scale.
pub(super) fn log_space(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| 10f64.powf(lo + (hi - lo) * i as f64 / (n - 1) as f64))
        .collect()
}

/// Reads a written figure back.
pub(super) fn load(path: &Path) -> Pixmap {
    Pixmap::load_png(path).expect("the figure is a PNG")
}

/// The colour at pixel `(x, y)`, rounded to the pixel grid.
pub(super) fn rgb_at(pixmap: &Pixmap, x: f32, y: f32) -> [u8; 3] {
    let p = pixmap
        .pixel(x.round() as u32, y.round() as u32)
        .expect("the pixel lies in the image");
    [p.red(), p.green(), p.blue()]
}

/// The 8-bit channels of an opaque colour.
pub(super) fn channels(color: ColorU8) -> [u8; 3] {
    [color.red(), color.green(), color.blue()]
}

/// Copies a sample figure to `$HOOKE_PLOT_SAMPLES` when it is set.
pub(super) fn keep(path: &Path) {
    if let Some(dir) = std::env::var_os("HOOKE_PLOT_SAMPLES") {
        let dir = PathBuf::from(dir);
        std::fs::create_dir_all(&dir).expect("sample directory");
        let name = path.file_name().expect("figure file name");
        std::fs::copy(path, dir.join(name)).expect("sample copied");
    }
}

#[test]
fn unwritable_path_is_an_io_error_naming_it() {
    let dir = TempDir::new().expect("temporary directory");
    let path = dir.path().join("missing").join("plot.png");
    let err = write_log_log(&log_log::sample_work_precision(), &path).expect_err("no directory");
    assert!(matches!(err, PlotError::Io { .. }), "{err:?}");
    assert!(err.to_string().contains(&*path.to_string_lossy()), "{err}");
    let err = write_heat_maps(&heat_map::sample_maps(), &path).expect_err("no directory");
    assert!(err.to_string().contains(&*path.to_string_lossy()), "{err}");
}

#[test]
fn ticks_are_labelled_powers_of_ten_thinned_to_fit() {
    let axis = LogAxis::new(-5.0, -1.0, 0.0, 400.0);
    let ticks = axis.ticks(|_| 50.0);
    let labels: Vec<_> = ticks.iter().filter_map(|t| t.label.as_deref()).collect();
    assert_eq!(labels, ["1e-5", "1e-4", "1e-3", "1e-2", "1e-1"]);
    assert!((ticks[2].pixel - 200.0).abs() < 1e-3);

    let crowded = LogAxis::new(-10.0, 2.0, 0.0, 300.0).ticks(|_| 60.0);
    assert_eq!(crowded.len(), 13);
    let labels: Vec<_> = crowded.iter().filter_map(|t| t.label.as_deref()).collect();
    assert_eq!(labels, ["1e-10", "1e-7", "1e-4", "1e-1", "1e2"]);

    let narrow = LogAxis::new(-3.9, -2.9, 0.0, 400.0).ticks(|_| 50.0);
    let labels: Vec<_> = narrow.iter().filter_map(|t| t.label.as_deref()).collect();
    assert_eq!(labels, ["2e-4", "5e-4", "1e-3"]);
}

#[test]
fn values_are_formatted_with_three_digits() {
    assert_eq!(format_value(1.0), "1");
    assert_eq!(format_value(2.345), "2.35");
    assert_eq!(format_value(600.0), "600");
    assert_eq!(format_value(12345.0), "1.23e4");
    assert_eq!(format_value(0.001), "1.00e-3");
}
