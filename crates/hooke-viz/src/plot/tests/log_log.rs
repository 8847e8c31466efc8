//! Log-log plots: size, points in place, bad and missing points.

use tempfile::TempDir;

use super::{NAMES, channels, keep, load, log_space, rgb_at};
use crate::plot::log_log::{PALETTE, plot_area};
use crate::plot::*;

/// Error against run time of the sample integrators, with bad points mixed in.
pub(super) fn sample_work_precision() -> LogLogPlot {
    let orders = [1.0, 1.0, 2.0, 4.0, 1.0, 1.0];
    let costs = [1.0, 1.1, 1.3, 4.2, 30.0, 12.0];
    let series = NAMES
        .iter()
        .zip(orders.iter().zip(costs))
        .map(|(name, (order, cost))| {
            let mut points: Vec<(f64, f64)> = log_space(-5.0, -2.0, 7)
                .into_iter()
                .map(|dt| (cost * 1e-5 / dt, 0.3 * (dt * 300.0f64).powf(*order)))
                .collect();
            points.push((f64::NAN, 1.0));
            points.push((1.0, -1.0));
            points.push((f64::INFINITY, 0.5));
            Series {
                label: (*name).to_owned(),
                points,
            }
        })
        .collect();
    LogLogPlot {
        title: "Work-precision: hanging cloth 20 × 20".to_owned(),
        x_label: "wall time (s)".to_owned(),
        y_label: "error (m)".to_owned(),
        series,
        reference: Some(Reference {
            y: 1e-3,
            label: "1 mm".to_owned(),
        }),
    }
}

#[test]
fn log_log_is_a_png_of_the_documented_size_with_points_in_place() {
    let dir = TempDir::new().expect("temporary directory");
    let path = dir.path().join("work_precision.png");
    let plot = sample_work_precision();
    write_log_log(&plot, &path).expect("figure written");
    keep(&path);
    let pixmap = load(&path);
    assert_eq!(
        (pixmap.width(), pixmap.height()),
        (LOG_LOG_WIDTH, LOG_LOG_HEIGHT)
    );

    // One series from (1e-3, 1e-6) to (1e-1, 1e-2): the axes span two and
    // four decades with 5 % to spare, so the first point lies 0.1/2.2 of the
    // way across and 0.2/4.4 of the way up.
    let single = LogLogPlot {
        series: vec![Series {
            label: "one".to_owned(),
            points: vec![(1e-3, 1e-6), (f64::NAN, 1.0), (1e-1, 1e-2)],
        }],
        reference: None,
        ..plot
    };
    let path = dir.path().join("single.png");
    write_log_log(&single, &path).expect("figure written");
    let pixmap = load(&path);
    let (x, y, w, h) = plot_area(&single);
    let first = (x + w * 0.1 / 2.2, y + h - h * 0.2 / 4.4);
    let last = (x + w * 2.1 / 2.2, y + h - h * 4.2 / 4.4);
    for (px, py) in [first, last] {
        assert_eq!(
            rgb_at(&pixmap, px, py),
            channels(PALETTE[0]),
            "marker at ({px}, {py})"
        );
    }
}

#[test]
fn convergence_plot_with_bad_and_missing_points_is_written() {
    let dir = TempDir::new().expect("temporary directory");
    let dts = log_space(-4.0, -2.0, 5);
    let series = [
        (1.0, "symplectic Euler"),
        (2.0, "velocity Verlet"),
        (4.0, "RK4"),
    ]
    .into_iter()
    .map(|(order, name)| Series {
        label: name.to_owned(),
        points: dts
            .iter()
            .map(|dt| (*dt, 2.0 * (dt * 50.0f64).powf(order)))
            .collect(),
    })
    .chain([
        Series {
            label: "explicit Euler (diverged)".to_owned(),
            points: dts.iter().map(|dt| (*dt, f64::INFINITY)).collect(),
        },
        Series {
            label: "none".to_owned(),
            points: Vec::new(),
        },
    ])
    .collect();
    let plot = LogLogPlot {
        title: "Convergence: hanging cloth 20 × 20, t = 1 s".to_owned(),
        x_label: "dt (s)".to_owned(),
        y_label: "error at t = 1 s (m)".to_owned(),
        series,
        reference: Some(Reference {
            y: 1e-3,
            label: "1 mm".to_owned(),
        }),
    };
    let path = dir.path().join("convergence.png");
    write_log_log(&plot, &path).expect("figure written");
    keep(&path);

    let nothing = LogLogPlot {
        series: vec![Series {
            label: "bad".to_owned(),
            points: vec![(0.0, 1.0), (f64::NAN, f64::NAN), (-1.0, f64::NEG_INFINITY)],
        }],
        reference: Some(Reference {
            y: f64::NAN,
            label: "nowhere".to_owned(),
        }),
        ..plot
    };
    let path = dir.path().join("nothing.png");
    write_log_log(&nothing, &path).expect("figure written");
    keep(&path);
    assert_eq!(load(&path).width(), LOG_LOG_WIDTH);
}

/// The `(cx, cy)` of every circle in an SVG document.
fn circles(svg: &str) -> Vec<(f32, f32)> {
    let attribute = |element: &str, name: &str| -> f32 {
        let start = element.find(&format!(" {name}=\"")).expect("attribute") + name.len() + 3;
        let end = start + element[start..].find('"').expect("closing quote");
        element[start..end].parse().expect("a number")
    };
    svg.lines()
        .filter(|line| line.starts_with("<circle"))
        .map(|line| (attribute(line, "cx"), attribute(line, "cy")))
        .collect()
}

#[test]
fn every_figure_has_an_svg_twin_with_its_markers_in_place_and_its_text_as_text() {
    let dir = TempDir::new().expect("temporary directory");
    let single = LogLogPlot {
        series: vec![Series {
            label: "one & only".to_owned(),
            points: vec![(1e-3, 1e-6), (f64::NAN, 1.0), (1e-1, 1e-2)],
        }],
        reference: None,
        ..sample_work_precision()
    };
    let path = dir.path().join("single.png");
    write_log_log(&single, &path).expect("figure written");
    let svg = std::fs::read_to_string(svg_path(&path)).expect("the SVG beside the PNG");
    assert!(svg.starts_with("<?xml") && svg.trim_end().ends_with("</svg>"));
    assert!(svg.contains(&format!("viewBox=\"0 0 {LOG_LOG_WIDTH} {LOG_LOG_HEIGHT}\"")));
    assert!(svg.contains(">Work-precision: hanging cloth 20 × 20</text>"));
    assert!(svg.contains(">one &amp; only</text>"));
    // The two finite points, where the PNG has them (see above), and the
    // legend's marker.
    let (x, y, w, h) = plot_area(&single);
    let drawn = circles(&svg);
    assert_eq!(drawn.len(), 3, "{drawn:?}");
    for (px, py) in [
        (x + w * 0.1 / 2.2, y + h - h * 0.2 / 4.4),
        (x + w * 2.1 / 2.2, y + h - h * 4.2 / 4.4),
    ] {
        assert!(
            drawn
                .iter()
                .any(|&(cx, cy)| (cx - px).abs() < 0.01 && (cy - py).abs() < 0.01),
            "no marker at ({px}, {py}) in {drawn:?}"
        );
    }

    let path = dir.path().join("maps.png");
    write_heat_maps(&super::heat_map::sample_maps(), &path).expect("figure written");
    let svg = std::fs::read_to_string(svg_path(&path)).expect("the SVG beside the PNG");
    assert!(svg.contains("<rect") && svg.contains("</text>"));
}
