//! The `hooke` binary itself, as a user runs it: exit codes and where its
//! messages go.

use std::process::Command;

fn hooke(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_hooke"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn check_of_the_default_scene_succeeds() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/stiff-cloth.toml");
    let output = hooke(&["check", scene]);
    assert!(output.status.success());
    let text = String::from_utf8(output.stdout).unwrap();
    assert!(text.contains("particles   1600 (0 pinned)"), "{text}");
    assert!(text.contains("obstacles   2"), "{text}");
}

#[test]
fn check_of_a_malformed_file_exits_with_1_and_the_message() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("broken.toml");
    std::fs::write(&path, "name = \"broken\"\n[simulation\n").unwrap();
    let output = hooke(&["check", path.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(1));
    let message = String::from_utf8(output.stderr).unwrap();
    assert!(message.starts_with("error: "), "{message}");
    assert!(message.contains("broken.toml:2"), "{message}");
    assert!(output.stdout.is_empty());
}

#[test]
fn unknown_arguments_exit_with_2() {
    let output = hooke(&["run", "--no-such-flag"]);
    assert_eq!(output.status.code(), Some(2));
}
