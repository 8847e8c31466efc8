//! Heat maps: size, cell colours at their grid positions, the h·ω = 2 line,
//! malformed and empty grids.

use tempfile::TempDir;

use super::{NAMES, channels, keep, load, log_space, rgb_at};
use crate::plot::heat_map::cells::{UNSTABLE, blend, edges};
use crate::plot::heat_map::{LINE, plot_area};
use crate::plot::*;

/// Stability maps of the sample integrators over a one-second run of a
/// scene with ω_max = 600 rad/s: explicit Euler's energy grows as
/// (1 + (hω)²)^(1/h), the symplectic methods' error stays bounded below their
/// limit hω < c, backward Euler is dissipative and its CG variant fails past
/// hω = 100.
pub(super) fn sample_maps() -> HeatMaps {
    let omega_max = 600.0;
    let dts = log_space(-6.0, -1.0, 21);
    let scales = log_space(0.0, 4.0, 13);
    let ratio = |name: &str, h_omega: f64, dt: f64| match name {
        "explicit Euler" => (1.0 + h_omega * h_omega).powf(1.0 / dt),
        "backward Euler" => 1.0,
        "backward Euler + CG" if h_omega > 100.0 => f64::NAN,
        "backward Euler + CG" => 1.0,
        _ => {
            let limit = if name == "RK4" { 2.8 } else { 2.0 };
            if h_omega < limit {
                1.0 + 0.2 * (h_omega / limit).powi(4)
            } else {
                f64::INFINITY
            }
        }
    };
    let panels = NAMES
        .iter()
        .map(|name| {
            let mut cells = Vec::new();
            for s in &scales {
                for dt in &dts {
                    let max_energy_ratio = ratio(name, dt * omega_max * s.sqrt(), *dt);
                    cells.push(Cell {
                        stable: max_energy_ratio < 10.0,
                        max_energy_ratio,
                    });
                }
            }
            HeatMapPanel {
                title: (*name).to_owned(),
                dts: dts.clone(),
                scales: scales.clone(),
                cells,
            }
        })
        .collect();
    HeatMaps {
        title: "Stability: hanging cloth 20 × 20".to_owned(),
        panels,
        omega_max: Some(omega_max),
    }
}

#[test]
fn heat_maps_are_a_png_of_the_documented_size() {
    let dir = TempDir::new().expect("temporary directory");
    let path = dir.path().join("stability.png");
    let maps = sample_maps();
    write_heat_maps(&maps, &path).expect("figure written");
    keep(&path);
    let pixmap = load(&path);
    let (width, height) = heat_maps_size(&maps);
    assert_eq!((pixmap.width(), pixmap.height()), (width, height));
    assert_eq!(width, 2 * 20 + HEAT_MAP_COLUMNS as u32 * 470);
    assert_eq!(height, 60 + 2 * 400 + 40 + 28);
}

/// A 3 × 3 grid over dt = 1e-4, 1e-3, 1e-2 and s = 1, 10, 100.
fn three_by_three(cells: Vec<Cell>, omega_max: Option<f64>) -> HeatMaps {
    HeatMaps {
        title: "grid".to_owned(),
        panels: vec![HeatMapPanel {
            title: "one".to_owned(),
            dts: vec![1e-4, 1e-3, 1e-2],
            scales: vec![1.0, 10.0, 100.0],
            cells,
        }],
        omega_max,
    }
}

/// Pixel centre of the cell in row `row` (scale) and column `column` (dt) of
/// a 3 × 3 grid: each cell takes a third of the plot area, rows upwards.
fn cell_centre(maps: &HeatMaps, row: usize, column: usize) -> (f32, f32) {
    let (x, y, w, h) = plot_area(maps, 0);
    let px = x + (column as f32 + 0.5) / 3.0 * w;
    let py = y + h - (row as f32 + 0.5) / 3.0 * h;
    (px, py)
}

#[test]
fn stable_and_unstable_cells_are_coloured_at_their_grid_position() {
    let stable = Cell {
        stable: true,
        max_energy_ratio: 1.0,
    };
    let unstable = Cell {
        stable: false,
        max_energy_ratio: 1e6,
    };
    let non_finite = Cell {
        stable: true,
        max_energy_ratio: f64::NAN,
    };
    // Unstable above the anti-diagonal, one non-finite stable cell at (s = 1, dt = 1e-2).
    let cells = (0..3)
        .flat_map(|row| (0..3).map(move |column| (row, column)))
        .map(|(row, column)| match (row, column) {
            (0, 2) => non_finite,
            _ if row + column >= 3 => unstable,
            _ => stable,
        })
        .collect();
    let dir = TempDir::new().expect("temporary directory");
    let path = dir.path().join("grid.png");
    let maps = three_by_three(cells, None);
    write_heat_maps(&maps, &path).expect("figure written");
    let pixmap = load(&path);
    let red = channels(UNSTABLE);
    for row in 0..3 {
        for column in 0..3 {
            let (px, py) = cell_centre(&maps, row, column);
            let got = rgb_at(&pixmap, px, py);
            let is_unstable = row + column >= 3 || (row, column) == (0, 2);
            if is_unstable {
                assert_eq!(got, red, "cell ({row}, {column}) at ({px}, {py})");
            } else {
                assert_ne!(got, red, "cell ({row}, {column}) at ({px}, {py})");
                assert!(
                    got[2] > got[0],
                    "stable cell ({row}, {column}) is blue: {got:?}"
                );
            }
        }
    }
}

#[test]
fn a_small_energy_gain_is_shaded_between_none_and_the_largest() {
    // Scale 1: no gain, a gain of 2.5e-5 of the allowance, the largest
    // (ratio 9); above it every cell lost energy (ratio 0.5).
    let ratios = [1.0, 1.0 + 2.5e-5, 9.0];
    let cells = (0..9)
        .map(|i| Cell {
            stable: true,
            max_energy_ratio: if i < 3 { ratios[i] } else { 0.5 },
        })
        .collect();
    let dir = TempDir::new().expect("temporary directory");
    let path = dir.path().join("gains.png");
    let maps = three_by_three(cells, None);
    write_heat_maps(&maps, &path).expect("figure written");
    let pixmap = load(&path);
    let at = |row, column| {
        let (px, py) = cell_centre(&maps, row, column);
        rgb_at(&pixmap, px, py)
    };
    let lightest = channels(blend(0.0));
    assert_eq!(at(0, 0), lightest);
    assert_eq!(at(1, 1), lightest);
    assert_eq!(at(0, 2), channels(blend(1.0)));
    // The log of the gain, from that of the floor to that of the largest.
    let floor = GAIN_FLOOR.log10();
    let t = ((2.5e-5_f64).log10() - floor) / (8.0_f64.log10() - floor);
    assert!(t > 0.4 && t < 0.5, "{t}");
    assert_eq!(at(0, 1), channels(blend(t as f32)));
}

#[test]
fn stability_line_crosses_the_cells_where_h_omega_is_two() {
    let cells = vec![
        Cell {
            stable: true,
            max_energy_ratio: 2.0,
        };
        9
    ];
    let dir = TempDir::new().expect("temporary directory");
    let path = dir.path().join("line.png");
    // ω_max = 2000: at s = 1 the line is at dt = 1e-3, at s = 100 at dt = 1e-4.
    let maps = three_by_three(cells, Some(2000.0));
    write_heat_maps(&maps, &path).expect("figure written");
    keep(&path);
    let pixmap = load(&path);
    let black = channels(LINE);
    for (row, column) in [(0, 1), (2, 0)] {
        let (px, py) = cell_centre(&maps, row, column);
        let got = rgb_at(&pixmap, px, py);
        let dark = got.iter().zip(black).all(|(g, b)| g.abs_diff(b) < 40);
        assert!(
            dark,
            "line at cell ({row}, {column}), ({px}, {py}): {got:?}"
        );
    }
    for (row, column) in [(0, 0), (2, 2)] {
        let (px, py) = cell_centre(&maps, row, column);
        let got = rgb_at(&pixmap, px, py);
        assert!(got[2] > 100, "no line at cell ({row}, {column}): {got:?}");
    }
}

#[test]
fn malformed_grids_are_errors_naming_the_file_and_panel() {
    let dir = TempDir::new().expect("temporary directory");
    let path = dir.path().join("bad.png");
    let mut maps = three_by_three(Vec::new(), Some(1.0));
    let err = write_heat_maps(&maps, &path).expect_err("no cells");
    assert!(matches!(
        err,
        PlotError::Grid {
            source: GridError::CellCount {
                expected: 9,
                found: 0
            },
            ..
        }
    ));
    assert!(err.to_string().contains("bad.png"), "{err}");
    maps.panels[0].dts[1] = f64::NAN;
    let err = write_heat_maps(&maps, &path).expect_err("NaN dt");
    assert!(matches!(
        err,
        PlotError::Grid {
            source: GridError::NotPositive {
                axis: "dts",
                index: 1,
                ..
            },
            ..
        }
    ));
    maps.panels[0].dts = vec![1e-3, 1e-3, 1e-2];
    let err = write_heat_maps(&maps, &path).expect_err("repeated dt");
    assert!(err.to_string().contains("dts[1]"), "{err}");
    assert!(!path.exists());
}

#[test]
fn empty_heat_maps_are_drawn_with_a_note() {
    let dir = TempDir::new().expect("temporary directory");
    let none = HeatMaps {
        title: "nothing".to_owned(),
        panels: Vec::new(),
        omega_max: Some(f64::NAN),
    };
    let path = dir.path().join("no_panels.png");
    write_heat_maps(&none, &path).expect("no panels");
    keep(&path);
    let mut empty = three_by_three(Vec::new(), None);
    empty.panels[0].dts.clear();
    let path = dir.path().join("empty.png");
    write_heat_maps(&empty, &path).expect("empty grid");
    let pixmap = load(&path);
    let (x, y, w, h) = plot_area(&empty, 0);
    let inked = (0..64)
        .map(|i| (x + w / 2.0 - 32.0 + i as f32, y + h / 2.0))
        .filter(|&(px, py)| rgb_at(&pixmap, px, py)[0] < 100)
        .count();
    assert!(
        inked > 4,
        "\"no data\" is written across the panel's middle"
    );
}

#[test]
fn too_many_panels_are_a_size_error_before_drawing() {
    let mut maps = three_by_three(Vec::new(), None);
    maps.panels[0].dts.clear();
    maps.panels = vec![maps.panels[0].clone(); 1000];
    let dir = TempDir::new().expect("temporary directory");
    let path = dir.path().join("huge.png");
    let err = write_heat_maps(&maps, &path).expect_err("1000 panels");
    assert!(matches!(err, PlotError::Size { .. }), "{err:?}");
    assert!(!path.exists());
}

#[test]
fn cell_edges_lie_half_way_between_grid_values() {
    let e = edges(&[1e-3, 1e-2, 1e-1]);
    let expected = [-3.5, -2.5, -1.5, -0.5];
    assert!(
        e.iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-12),
        "{e:?}"
    );
    let lone = edges(&[1.0]);
    assert!(
        lone.iter()
            .zip([-0.5, 0.5])
            .all(|(a, b)| (a - b).abs() < 1e-12),
        "{lone:?}"
    );
}
