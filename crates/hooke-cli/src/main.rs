//! The `hooke` command: `cargo run --release` from the workspace root runs
//! the default scene.

fn main() -> std::process::ExitCode {
    hooke_cli::main()
}
