//! Turns criterion results into the markdown table of docs/performance.md (`cargo bench-table`).
//!
//! Reads `<criterion dir>/<group>/*/*/new/{benchmark,estimates}.json` as written by
//! `cargo bench --bench jbearing_benches -- <group>` and prints, in markdown:
//!
//! - the machine (model name and logical CPU count from `/proc/cpuinfo`) and the date of the
//!   newest measurement (modification time of its `estimates.json`, UTC);
//! - a table of median time per unknown (ns): one row per bench function, one column per
//!   parameter (the line length m). "Per unknown" is the median time per iteration divided by
//!   the bench's declared criterion throughput (elements = unknowns solved per iteration);
//! - for the `kernel` group, the ratios behind the performance targets of issue 2, item 5, each
//!   marked met or missed.
//!
//! Usage: `cargo bench-table [GROUP] [--criterion-dir DIR] [--write-docs]`; GROUP defaults to
//! `kernel`, DIR to `$CARGO_TARGET_DIR/criterion` or the workspace's `target/criterion`.
//! `--write-docs` also puts the output into docs/performance.md, in place of the block between
//! `<!-- BEGIN generated: cargo bench-table -->` (`cargo bench-table GROUP` for another group)
//! and `<!-- END generated -->`.
use anyhow::{Context, Result, bail};
use jbearing_validation::generated_docs::{docs_page, machine, take_report, write_generated_block};
use jbearing_validation::{report, report_part};
use serde_json::Value;
use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// One measured bench: median ns per unknown.
struct Measured {
    ns_per_unknown: f64,
    modified: SystemTime,
}

/// function id → parameter (m) → measurement.
type Results = BTreeMap<String, BTreeMap<u64, Measured>>;

fn main() -> Result<()> {
    let mut group = "kernel".to_string();
    let mut dir: Option<PathBuf> = None;
    let mut write_docs = false;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--criterion-dir" => {
                dir = Some(args.next().context("--criterion-dir needs a path")?.into())
            }
            "--write-docs" => write_docs = true,
            "-h" | "--help" => {
                println!("usage: bench_table [GROUP] [--criterion-dir DIR] [--write-docs]");
                return Ok(());
            }
            _ => group = a,
        }
    }
    let dir = dir.unwrap_or_else(|| {
        std::env::var_os("CARGO_TARGET_DIR")
            .map(PathBuf::from)
            .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../target"))
            .join("criterion")
    });
    let results = read_group(&dir.join(&group)).with_context(|| {
        format!(
            "reading criterion results of group {group} in {}",
            dir.display()
        )
    })?;
    if results.is_empty() {
        bail!(
            "no results under {}; run `cargo bench --bench jbearing_benches -- {group}` first",
            dir.join(&group).display()
        );
    }
    let newest = results
        .values()
        .flat_map(|r| r.values().map(|m| m.modified))
        .max()
        .unwrap_or(SystemTime::UNIX_EPOCH);
    report!("Machine: {}. Measured: {}.", machine(), utc(newest));
    report!();
    print_table(&results);
    if group == "kernel" {
        report!();
        print_kernel_ratios(&results);
    }
    if write_docs {
        let command = if group == "kernel" {
            "cargo bench-table".to_string()
        } else {
            format!("cargo bench-table {group}")
        };
        let page = docs_page("performance.md");
        write_generated_block(&page, &command, &take_report())?;
        eprintln!("wrote the block of {command:?} in {}", page.display());
    }
    Ok(())
}

fn read_group(group_dir: &Path) -> Result<Results> {
    let mut out = Results::new();
    for function in fs::read_dir(group_dir)? {
        let function = function?.path();
        if !function.is_dir() || function.file_name().is_some_and(|n| n == "report") {
            continue;
        }
        for param in fs::read_dir(&function)? {
            let new = param?.path().join("new");
            let (bench_json, est_json) = (new.join("benchmark.json"), new.join("estimates.json"));
            if !bench_json.is_file() || !est_json.is_file() {
                continue;
            }
            let bench: Value = serde_json::from_str(&fs::read_to_string(&bench_json)?)
                .with_context(|| bench_json.display().to_string())?;
            let est: Value = serde_json::from_str(&fs::read_to_string(&est_json)?)
                .with_context(|| est_json.display().to_string())?;
            let function_id = bench["function_id"]
                .as_str()
                .with_context(|| format!("no function_id in {}", bench_json.display()))?;
            let Some(m) = bench["value_str"]
                .as_str()
                .and_then(|v| v.parse::<u64>().ok())
            else {
                continue;
            };
            let unknowns = bench["throughput"]["Elements"]
                .as_u64()
                .with_context(|| format!("no element throughput in {}", bench_json.display()))?;
            let median_ns = est["median"]["point_estimate"]
                .as_f64()
                .with_context(|| format!("no median in {}", est_json.display()))?;
            out.entry(function_id.to_string()).or_default().insert(
                m,
                Measured {
                    ns_per_unknown: median_ns / unknowns as f64,
                    modified: fs::metadata(&est_json)?.modified()?,
                },
            );
        }
    }
    Ok(out)
}

/// Order of the kernel rows (others after, alphabetically).
const KERNEL_ORDER: [&str; 9] = [
    "modified_thomas",
    "plain_thomas",
    "sherman_morrison",
    "faer_sparse_lu",
    "faer_sparse_lu_reused_symbolic",
    "nalgebra_dense_lu",
    "batched_32_lines",
    "factored_32_lines",
    "loop_32_lines",
];

fn print_table(results: &Results) {
    let mut params: Vec<u64> = results.values().flat_map(|r| r.keys().copied()).collect();
    params.sort_unstable();
    params.dedup();
    let mut names: Vec<&String> = results.keys().collect();
    names.sort_by_key(|n| {
        (
            KERNEL_ORDER
                .iter()
                .position(|k| k == n)
                .unwrap_or(usize::MAX),
            n.to_string(),
        )
    });
    report_part!("| median ns per unknown |");
    for m in &params {
        report_part!(" m = {m} |");
    }
    report!();
    report_part!("|---|");
    for _ in &params {
        report_part!("---:|");
    }
    report!();
    for name in names {
        report_part!("| {name} |");
        for m in &params {
            match results[name].get(m) {
                Some(v) => report_part!(" {} |", fmt(v.ns_per_unknown)),
                None => report_part!(" – |"),
            }
        }
        report!();
    }
}

fn fmt(v: f64) -> String {
    if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}

/// A performance target: its text, at which m it applies, and whether a ratio meets it.
type Target = (&'static str, fn(u64) -> bool, fn(f64) -> bool);

/// A ratio of two benches' ns per unknown at each m, with a target.
struct Ratio {
    what: &'static str,
    num: &'static str,
    den: &'static str,
    /// Target: (applies at m, passes?) — None for an informative ratio.
    target: Option<Target>,
}

/// The ratios behind the performance targets of issue 2, item 5, and the informative ones.
fn kernel_ratios() -> [Ratio; 7] {
    [
        Ratio {
            what: "modified Thomas / plain Thomas",
            num: "modified_thomas",
            den: "plain_thomas",
            target: Some(("≤ 1.3 for m ≥ 256", |m| m >= 256, |r| r <= 1.3)),
        },
        Ratio {
            what: "Sherman–Morrison / modified Thomas",
            num: "sherman_morrison",
            den: "modified_thomas",
            target: Some(("> 1 (modified Thomas faster)", |_| true, |r| r > 1.0)),
        },
        Ratio {
            what: "faer sparse LU (factor + solve) / modified Thomas",
            num: "faer_sparse_lu",
            den: "modified_thomas",
            target: Some(("≥ 20 at m = 256", |m| m == 256, |r| r >= 20.0)),
        },
        Ratio {
            what: "faer sparse LU, reused symbolic / modified Thomas",
            num: "faer_sparse_lu_reused_symbolic",
            den: "modified_thomas",
            target: None,
        },
        Ratio {
            what: "nalgebra dense LU / modified Thomas",
            num: "nalgebra_dense_lu",
            den: "modified_thomas",
            target: None,
        },
        Ratio {
            what: "loop of 32 single-line solves / batched 32 lines",
            num: "loop_32_lines",
            den: "batched_32_lines",
            target: Some(("≥ 2 (throughput)", |_| true, |r| r >= 2.0)),
        },
        Ratio {
            what: "batched 32 lines (factor + solve) / factored once, solve only",
            num: "batched_32_lines",
            den: "factored_32_lines",
            target: None,
        },
    ]
}

/// The kernel group's ratio table: a column per line length m, a row per ratio whose two
/// benches were measured, each with its target and verdict.
fn print_kernel_ratios(results: &Results) {
    let mut params: Vec<u64> = results.values().flat_map(|r| r.keys().copied()).collect();
    params.sort_unstable();
    params.dedup();
    report_part!("| ratio of ns per unknown |");
    for m in &params {
        report_part!(" m = {m} |");
    }
    report!(" target | verdict |");
    report_part!("|---|");
    for _ in &params {
        report_part!("---:|");
    }
    report!("---|---|");
    for r in &kernel_ratios() {
        let (Some(num), Some(den)) = (results.get(r.num), results.get(r.den)) else {
            continue;
        };
        print_ratio_row(r, num, den, &params);
    }
}

/// One ratio's row: num / den at each m ("–" where one is missing), the target and whether the
/// ratios it applies to meet it.
fn print_ratio_row(
    r: &Ratio,
    num: &BTreeMap<u64, Measured>,
    den: &BTreeMap<u64, Measured>,
    params: &[u64],
) {
    report_part!("| {} |", r.what);
    let mut verdict: Option<bool> = None;
    let mut judged = Vec::new();
    for m in params {
        match (num.get(m), den.get(m)) {
            (Some(a), Some(b)) => {
                let q = a.ns_per_unknown / b.ns_per_unknown;
                report_part!(" {q:.2} |");
                if let Some((_, applies, passes)) = r.target
                    && applies(*m)
                {
                    let ok = passes(q);
                    verdict = Some(verdict.unwrap_or(true) && ok);
                    judged.push(format!("{q:.2}"));
                }
            }
            _ => report_part!(" – |"),
        }
    }
    match (r.target, verdict) {
        (Some((t, _, _)), Some(ok)) => report!(
            " {t} | {} ({}) |",
            if ok { "met" } else { "missed" },
            judged.join(", ")
        ),
        (Some((t, _, _)), None) => report!(" {t} | not measured |"),
        (None, _) => report!(" (information) | |"),
    }
}

/// "YYYY-MM-DD HH:MM UTC" of a system time (civil-from-days, Howard Hinnant's algorithm).
fn utc(t: SystemTime) -> String {
    jiff::Timestamp::try_from(t)
        .map(|ts| ts.strftime("%Y-%m-%d %H:%M UTC").to_string())
        .unwrap_or_else(|_| "unknown date".to_string())
}
