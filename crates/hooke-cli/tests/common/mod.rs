//! What the command-line tests share.

use std::process::ExitCode;

use hooke_cli::run_cli;

/// Runs `hooke ARGS...` and returns the exit code, standard output and
/// standard error.
pub fn hooke(args: &[&str]) -> (ExitCode, String, String) {
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let argv = std::iter::once("hooke").chain(args.iter().copied());
    let code = run_cli(argv, &mut out, &mut err);
    let text = |bytes| String::from_utf8(bytes).unwrap();
    (code, text(out), text(err))
}
