//! The `ontogeny` command. Thin: it parses flags and calls the library.

mod cli;

use std::process::ExitCode;

fn main() -> ExitCode {
    cli::main()
}
