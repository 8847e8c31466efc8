//! The `hooke` command: `cargo run --release` runs the default scene.

fn main() -> std::process::ExitCode {
    hooke_cli::main()
}
