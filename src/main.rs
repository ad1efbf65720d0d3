//! `jbearing`: command-line front end. The application (case files, batch runs, HDF5 output,
//! plots) lives in the library half of this package; `main` only parses and dispatches.

use clap::Parser;

fn main() -> std::process::ExitCode {
    jbearing::cli::main_with(jbearing::cli::Cli::parse())
}
