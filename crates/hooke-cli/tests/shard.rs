//! Sweeps across machines: `hooke stability` and `hooke accuracy` run as
//! three shards and combined by `hooke merge` write the same reports as
//! the unsharded runs, every value but the wall times equal.

mod common;

use std::path::Path;
use std::process::ExitCode;

use common::hooke;
use serde_json::Value;

fn json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// `value` without its wall times, at any depth.
fn without_wall_times(mut value: Value) -> Value {
    match &mut value {
        Value::Object(map) => {
            map.remove("wall_s");
            for item in map.values_mut() {
                *item = without_wall_times(item.take());
            }
        }
        Value::Array(items) => {
            for item in items.iter_mut() {
                *item = without_wall_times(item.take());
            }
        }
        _ => {}
    }
    value
}

/// The rows of a CSV table without its `wall_s` column (no field of
/// these tables holds a comma).
fn csv_without_wall_times(path: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let rows: Vec<Vec<String>> = text
        .lines()
        .map(|line| line.split(',').map(str::to_owned).collect())
        .collect();
    let wall = rows[0].iter().position(|c| c == "wall_s").unwrap();
    rows.into_iter()
        .map(|mut row| {
            row.remove(wall);
            row
        })
        .collect()
}

/// Runs `command ARGS` whole into `dir/whole` and as three shards merged
/// into `dir/merged`; returns the two reports `name` without wall times.
fn whole_and_merged(dir: &Path, command: &str, args: &[&str], name: &str) -> (Value, Value) {
    let run = |extra: &[&str]| {
        let all: Vec<&str> = [command]
            .iter()
            .chain(args)
            .chain(extra)
            .chain(&["-q"])
            .copied()
            .collect();
        let (code, stdout, stderr) = hooke(&all);
        assert_eq!(code, ExitCode::SUCCESS, "{all:?}: {stdout}\n{stderr}");
    };
    let whole = dir.join("whole");
    run(&["--out", whole.to_str().unwrap()]);
    let parts: Vec<String> = (0..3)
        .map(|i| dir.join(format!("part{i}")).to_str().unwrap().to_owned())
        .collect();
    for (i, part) in parts.iter().enumerate() {
        run(&["--shard", &format!("{i}/3"), "--out", part]);
        assert!(
            !Path::new(part).join(name).exists(),
            "a part writes no whole report"
        );
    }
    let merged = dir.join("merged");
    let mut merge = vec!["merge", "--out", merged.to_str().unwrap()];
    // The parts in another order than their indices: merge sorts them.
    merge.extend([&parts[2], &parts[0], &parts[1]].map(String::as_str));
    let (code, stdout, stderr) = hooke(&merge);
    assert_eq!(code, ExitCode::SUCCESS, "{stdout}\n{stderr}");
    let csv = format!("{}.csv", name.trim_end_matches(".json"));
    assert_eq!(
        csv_without_wall_times(&whole.join(&csv)),
        csv_without_wall_times(&merged.join(&csv))
    );
    (
        without_wall_times(json(&whole.join(name))),
        without_wall_times(json(&merged.join(name))),
    )
}

#[test]
fn a_stability_sweep_in_three_shards_merges_into_the_unsharded_report() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "--builtin",
        "oscillator",
        "--methods",
        "explicit-euler,symplectic-euler,rk4,backward-euler",
        "--stiffness",
        "1:100:3",
        "--dt",
        "1e-3:1e-1:4",
        "--duration",
        "0.1",
        "--limit",
    ];
    let (whole, merged) = whole_and_merged(dir.path(), "stability", &args, "stability.json");
    assert_eq!(whole["cells"].as_array().unwrap().len(), 4 * 3 * 4);
    assert_eq!(whole["limits"].as_array().unwrap().len(), 4);
    assert_eq!(merged, whole);
    for figure in ["stability.png", "stability.svg", "stability.csv"] {
        assert!(dir.path().join("merged").join(figure).is_file(), "{figure}");
    }
}

#[test]
fn an_accuracy_measurement_in_three_shards_merges_into_the_unsharded_report() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "--builtin",
        "damped-oscillator",
        "--methods",
        "velocity-verlet,rk4,dormand-prince",
        "--dt",
        "0.002:0.016:4",
        "--tolerances",
        "1e-4,1e-6",
        "--repeat",
        "1",
    ];
    let (whole, merged) = whole_and_merged(dir.path(), "accuracy", &args, "accuracy.json");
    assert_eq!(whole["runs"].as_array().unwrap().len(), 4 + 4 + 2);
    assert_eq!(whole["orders"].as_array().unwrap().len(), 3);
    assert_eq!(merged, whole);
    for figure in ["work_precision.svg", "convergence.svg", "accuracy.csv"] {
        assert!(dir.path().join("merged").join(figure).is_file(), "{figure}");
    }
}

#[test]
fn merging_parts_of_different_sweeps_or_missing_parts_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let part = |i: usize, n: usize, dt: &str| {
        let out = dir.path().join(format!("p{i}of{n}{dt}"));
        let (code, stdout, stderr) = hooke(&[
            "stability",
            "--builtin",
            "oscillator",
            "--methods",
            "rk4",
            "--stiffness",
            "1",
            "--dt",
            dt,
            "--duration",
            "0.01",
            "--min-steps",
            "10",
            "--shard",
            &format!("{i}/{n}"),
            "--out",
            out.to_str().unwrap(),
            "-q",
        ]);
        assert_eq!(code, ExitCode::SUCCESS, "{stdout}\n{stderr}");
        out.to_str().unwrap().to_owned()
    };
    let merge = |dirs: &[&str]| {
        let mut args = vec!["merge", "--out", "/nonexistent/never-written"];
        args.extend(dirs);
        let (code, _, stderr) = hooke(&args);
        assert_eq!(code, ExitCode::FAILURE);
        stderr
    };
    let (a, b) = (part(0, 2, "0.01,0.02"), part(1, 2, "0.01,0.02"));
    let stderr = merge(&[&a]);
    assert!(stderr.contains("shards [0] of 2"), "{stderr}");
    let other = part(1, 2, "0.01,0.03");
    let stderr = merge(&[&a, &other]);
    assert!(stderr.contains("cannot merge"), "{stderr}");
    let stderr = merge(&[dir.path().to_str().unwrap()]);
    assert!(stderr.contains("no stability.shard-*.json"), "{stderr}");
    let (code, _, stderr) = hooke(&["stability", "--shard", "3/3"]);
    assert_eq!(code, ExitCode::from(2), "{stderr}");
    assert!(stderr.contains("--shard"), "{stderr}");
    drop(b);
}
