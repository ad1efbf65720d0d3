//! The compressor table of docs/results.md from the batch's output: reads
//! `results/compressor_main_summary.csv` and `results/compressor_rod_summary.csv` (written by
//! `bash scripts/run_compressor.sh`, one row per quantity, a column per method, SI units) and
//! prints one markdown row per bearing and method: T_eff / T_out, μ_eff, the cycle minimum of
//! h_min, the maximum ε, the cycle means of the side flow and the power loss, the peak pressure,
//! the mobility method's deviation from the rigorous one as the application computed it
//! (`mobility_deviation_percent`), and each method's status. It measures nothing itself: the
//! first line names the machine it runs on (the batch's, when run right after it) and the time
//! the summaries were written.
//!
//! Usage: `bash scripts/run_compressor.sh && cargo run --release -p jbearing-validation --bin
//! results_table [-- [--results DIR] [--write-docs]]` (`--results`: where the batch wrote, default
//! the workspace's `results/`; `--write-docs`: also put the table into docs/results.md in place of
//! the block `<!-- BEGIN generated: COMMAND -->` … `<!-- END generated -->`, COMMAND being
//! `bash scripts/run_compressor.sh && cargo run --release -p jbearing-validation --bin
//! results_table`).

use anyhow::{Context, Result, bail};
use jbearing_validation::generated_docs::{
    docs_page, fixed, machine, signed, take_report, write_generated_block,
};
use jbearing_validation::report;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The name of the block in docs/results.md.
const COMMAND: &str = "bash scripts/run_compressor.sh && cargo run --release -p jbearing-validation --bin results_table";

/// The cases of the batch, in the table's order.
const CASES: [&str; 2] = ["compressor_main", "compressor_rod"];

/// One `CASE_summary.csv`: quantity → (rigorous, mobility, mobility_deviation_percent), cells
/// as written (empty where a method has no value).
struct Summary {
    rows: HashMap<String, [String; 3]>,
}

impl Summary {
    fn read(path: &Path) -> Result<Self> {
        let mut r = csv::Reader::from_path(path).with_context(|| format!("{}", path.display()))?;
        let header = r.headers()?.clone();
        let col = |name: &str| {
            header
                .iter()
                .position(|h| h == name)
                .with_context(|| format!("{}: no column {name:?}", path.display()))
        };
        let (q, rig, mob, dev) = (
            col("quantity")?,
            col("rigorous")?,
            col("mobility")?,
            col("mobility_deviation_percent")?,
        );
        let mut rows = HashMap::new();
        for rec in r.records() {
            let rec = rec.with_context(|| format!("{}", path.display()))?;
            let cell = |i: usize| rec.get(i).unwrap_or("").to_string();
            rows.insert(cell(q), [cell(rig), cell(mob), cell(dev)]);
        }
        Ok(Self { rows })
    }

    /// The cell of `quantity` for method column `m` (0 rigorous, 1 mobility, 2 deviation).
    fn cell(&self, quantity: &str, m: usize) -> Option<&str> {
        self.rows
            .get(quantity)
            .map(|r| r[m].as_str())
            .filter(|c| !c.is_empty())
    }

    /// The number of `quantity` for method column `m`, scaled; an error if it is missing or not
    /// a number (the table never shows a blank where the batch should have written a value).
    fn number(&self, quantity: &str, m: usize, scale: f64) -> Result<f64> {
        let c = self
            .cell(quantity, m)
            .with_context(|| format!("no value of {quantity} (column {m})"))?;
        let v: f64 = c
            .parse()
            .with_context(|| format!("{quantity}: {c:?} is not a number"))?;
        if !v.is_finite() {
            bail!("{quantity}: {v} is not finite");
        }
        Ok(scale * v)
    }
}

fn main() -> Result<()> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let write_docs = args.iter().any(|a| a == "--write-docs");
    args.retain(|a| a != "--write-docs");
    let results: PathBuf = match args.as_slice() {
        [] => Path::new(env!("CARGO_MANIFEST_DIR")).join("../results"),
        [flag, dir] if flag == "--results" => PathBuf::from(dir),
        other => bail!("unexpected arguments {other:?} (expected --results DIR, --write-docs)"),
    };
    let mut summaries = Vec::new();
    let mut written = None;
    for case in CASES {
        let path = results.join(format!("{case}_summary.csv"));
        let modified = std::fs::metadata(&path)
            .and_then(|m| m.modified())
            .with_context(|| format!("{} (run bash scripts/run_compressor.sh)", path.display()))?;
        written = written.max(Some(modified));
        summaries.push((case, Summary::read(&path)?));
    }
    let written = jiff::Timestamp::try_from(written.expect("two cases"))
        .context("summary file time")?
        .strftime("%Y-%m-%d %H:%M UTC");
    report!(
        "Machine: {}. Summaries written: {written} by `bash scripts/run_compressor.sh` (release \
         build; both bearings in parallel, one core each). Deviations: mobility against rigorous.\n",
        machine(),
    );
    report!(
        "| bearing | method | T_eff / T_out [°C] | μ_eff [mPa·s] | h_min, cycle min [µm] | ε max | side flow, mean [cm³/s] | power loss, mean [W] | peak pressure [MPa] | status |"
    );
    report!("|---|---|---|---|---|---|---|---|---|---|");
    for (case, s) in &summaries {
        for (m, method) in [
            (0, "rigorous (JFO, inverse)"),
            (1, "mobility (finite-length map)"),
        ] {
            let context = || format!("{case}, {method}");
            let value = |q: &str, scale: f64, decimals: usize| -> Result<String> {
                let v = fixed(s.number(q, m, scale).with_context(context)?, decimals);
                // The mobility row carries its deviation from the rigorous one.
                Ok(match (m, s.cell(q, 2).map(str::parse::<f64>)) {
                    (1, Some(Ok(d))) => format!("{v} ({} %)", signed(d, 1)),
                    _ => v,
                })
            };
            let plain = |q: &str, scale: f64, decimals: usize| -> Result<String> {
                Ok(fixed(
                    s.number(q, m, scale).with_context(context)?,
                    decimals,
                ))
            };
            report!(
                "| {case} | {method} | {} / {} | {} | {} | {} | {} | {} | {} | {} |",
                plain("effective_temperature", 1.0, 1)?,
                plain("outlet_temperature", 1.0, 1)?,
                plain("effective_viscosity", 1e3, 1)?,
                value("min_film_thickness_min", 1e6, 2)?,
                plain("eccentricity_ratio_max", 1.0, 3)?,
                value("side_leakage_mean", 1e6, 3)?,
                value("power_loss_mean", 1.0, 1)?,
                value("max_pressure_max", 1e-6, 2)?,
                s.cell("status", m).unwrap_or("not run"),
            );
        }
    }
    if write_docs {
        let page = docs_page("results.md");
        write_generated_block(&page, COMMAND, &take_report())
            .with_context(|| format!("writing the block into {}", page.display()))?;
        eprintln!("wrote the block of {COMMAND:?} in {}", page.display());
    }
    Ok(())
}
