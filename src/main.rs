//! `jbearing`: command-line front end. The application (case files, batch runs, HDF5 output,
//! plots) lives in the library half of this package; `main` only parses and dispatches.

use clap::Parser;

/// Dynamically loaded journal bearings with mass-conserving (JFO) cavitation.
#[derive(Debug, Parser)]
#[command(version, about, long_about = None)]
struct Cli {}

fn main() -> anyhow::Result<()> {
    let _cli = Cli::parse();
    Ok(())
}
