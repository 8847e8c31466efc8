//! The Python package's tests, run by `cargo test`: builds the package
//! with maturin into a virtual environment under the target directory
//! (made, and given `tests/requirements.txt` from PyPI, on the first run;
//! reused after), then runs pytest on `tests/pytest/` and fails with its
//! output. The interpreter is `python3` on the `PATH`, or `$HOOKE_PYTHON`.
//!
//! The package is built with the profile of the test build (the dev
//! profile, which optimises dependencies and, lightly, the workspace), in
//! the workspace's target directory, so it shares what the test build
//! already compiled.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs `command`, failing the test with its output when it fails.
fn run(command: &mut Command, what: &str) -> Output {
    let output = command
        .output()
        .unwrap_or_else(|e| panic!("{what}: cannot start {command:?}: {e}"));
    assert!(
        output.status.success(),
        "{what} failed ({}):\n{}\n{}",
        output.status,
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

/// The virtual environment, with the requirements installed: made on
/// the first run, refreshed when `requirements.txt` changes.
fn environment(crate_dir: &Path) -> PathBuf {
    let venv = Path::new(env!("CARGO_TARGET_TMPDIR")).join("hooke-py-venv");
    let python = venv.join("bin").join("python");
    if !python.exists() {
        let interpreter = std::env::var("HOOKE_PYTHON").unwrap_or_else(|_| "python3".into());
        run(
            Command::new(interpreter).args(["-m", "venv"]).arg(&venv),
            "making the virtual environment",
        );
    }
    let requirements = crate_dir.join("tests").join("requirements.txt");
    let wanted = std::fs::read_to_string(&requirements).expect("tests/requirements.txt");
    let stamp = venv.join("requirements.txt");
    if std::fs::read_to_string(&stamp).ok().as_deref() != Some(wanted.as_str()) {
        run(
            Command::new(&python)
                .args([
                    "-m",
                    "pip",
                    "install",
                    "--quiet",
                    "--disable-pip-version-check",
                    "-r",
                ])
                .arg(&requirements),
            "installing the test requirements",
        );
        std::fs::write(&stamp, wanted).expect("the requirements stamp");
    }
    venv
}

#[test]
fn the_python_package_passes_its_tests() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let venv = environment(crate_dir);
    let bin = venv.join("bin");
    let wheels = Path::new(env!("CARGO_TARGET_TMPDIR")).join("hooke-py-wheels");
    // A wheel left by an earlier build would be installed beside the new one.
    let _ = std::fs::remove_dir_all(&wheels);
    run(
        Command::new(bin.join("maturin"))
            .args(["build", "--quiet", "--out"])
            .arg(&wheels)
            .current_dir(crate_dir)
            .env("VIRTUAL_ENV", &venv),
        "building the package",
    );
    let wheel = std::fs::read_dir(&wheels)
        .expect("the wheel directory")
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .find(|path| path.extension().is_some_and(|e| e == "whl"))
        .expect("a wheel");
    run(
        Command::new(bin.join("python"))
            .args([
                "-m",
                "pip",
                "install",
                "--quiet",
                "--disable-pip-version-check",
                "--no-deps",
                "--force-reinstall",
            ])
            .arg(&wheel),
        "installing the package",
    );
    let output = run(
        Command::new(bin.join("python"))
            .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
            .arg(crate_dir.join("tests").join("pytest"))
            // No bytecode caches in the source tree.
            .env("PYTHONDONTWRITEBYTECODE", "1")
            .current_dir(Path::new(env!("CARGO_TARGET_TMPDIR"))),
        "pytest",
    );
    let report = String::from_utf8_lossy(&output.stdout);
    // The closing line, e.g. "42 passed in 61.20s".
    eprintln!("pytest: {}", report.lines().last().unwrap_or_default());
}
