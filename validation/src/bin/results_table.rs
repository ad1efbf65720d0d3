//! The compressor table of docs/results.md from the batch's output: reads
//! `results/compressor_main_summary.csv` and `results/compressor_rod_summary.csv` (written by
//! `bash scripts/run_compressor.sh`, one row per quantity, a column per method, SI units) and
//! prints one markdown row per bearing and method: T_eff / T_out, μ_eff, the cycle minimum of
//! h_min, the maximum ε, the cycle means of the side flow and the power loss, the peak pressure,
//! the mobility method's deviation from the rigorous one as the application computed it
//! (`mobility_deviation_percent`), and each method's status; then the step-to-step smoothness
//! of each bearing's side leakage and supply flow over the periodic cycle, with the drive's
//! beside them (`jbearing_validation::smoothness`, read from `results/CASE.h5`). It measures
//! nothing itself: the
//! first line names the machine it runs on (the batch's, when run right after it) and the time
//! the summaries were written.
//!
//! Usage: `bash scripts/run_compressor.sh && cargo run --release -p jbearing-validation --bin
//! results_table [-- [--results DIR] [--write-docs]]` (`--results`: where the batch wrote, default
//! the workspace's `results/`; `--write-docs`: also put the table into docs/results.md in place of
//! the block `<!-- BEGIN generated: COMMAND -->` … `<!-- END generated -->`, COMMAND being
//! `bash scripts/run_compressor.sh && cargo run --release -p jbearing-validation --bin
//! results_table`).
//!
//! With `--elastic`: the table of docs/validation.md, "Deformable bearing under a dynamic load"
//! — the compressor rod bearing rigid (`cases/compressor_rod_rigid87.toml`) against elastic
//! (`cases/compressor_rod_elastic.toml`, and `compressor_rod_elastic_gap1e-4` if its output is
//! there), from each run's `CASE_summary.csv` (h_min, ε, power, side flow, status) and the
//! rigorous group's attributes in `CASE.h5` (cycles, periodic, stalled steps, film step and
//! Jacobian evaluations) and its `wall_time_s`; the block is [`ELASTIC_COMMAND`].

use anyhow::{Context, Result, bail};
use jbearing_validation::generated_docs::{
    docs_page, fixed, machine, signed, take_report, write_generated_block,
};
use jbearing_validation::report;
use jbearing_validation::smoothness::smoothness;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The name of the block in docs/results.md.
const COMMAND: &str = "bash scripts/run_compressor.sh && cargo run --release -p jbearing-validation --bin results_table";

/// The name of the elastic block in docs/validation.md.
const ELASTIC_COMMAND: &str = "cargo run --release -- run cases/compressor_rod_rigid87.toml --out results/ && cargo run --release -- run cases/compressor_rod_elastic.toml --out results/ && cargo run --release -p jbearing-validation --bin results_table -- --elastic";

/// The rows of the elastic table: case name, film label; a row whose files are missing is an
/// error except the optional last one (the looser gap tolerance).
const ELASTIC_CASES: [(&str, &str, bool); 3] = [
    ("compressor_rod_rigid87", "rigid", true),
    (
        "compressor_rod_elastic",
        "elastic (default gap tolerance, 1e-8 c)",
        true,
    ),
    (
        "compressor_rod_elastic_gap1e-4",
        "elastic (gap tolerance 1e-4 c)",
        false,
    ),
];

/// The cases of the batch, in the table's order.
const CASES: [&str; 2] = ["compressor_main", "compressor_rod"];

/// The method columns of a summary, in the table's order.
const METHODS: [(usize, &str); 2] = [
    (0, "rigorous (JFO, inverse)"),
    (1, "mobility (finite-length map)"),
];

/// One `CASE_summary.csv`: quantity → (rigorous, mobility, mobility_deviation_percent), cells
/// as written (empty where a method has no value).
struct Summary {
    path: PathBuf,
    rows: HashMap<String, [String; 3]>,
}

impl Summary {
    fn read(path: &Path) -> Result<Self> {
        let mut r = csv::Reader::from_path(path).with_context(|| format!("{}", path.display()))?;
        let header = r
            .headers()
            .with_context(|| format!("{}", path.display()))?
            .clone();
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
        Ok(Self {
            path: path.to_path_buf(),
            rows,
        })
    }

    /// The cell of `quantity` for method column `m` (0 rigorous, 1 mobility, 2 deviation).
    fn cell(&self, quantity: &str, m: usize) -> Option<&str> {
        self.rows
            .get(quantity)
            .map(|r| r[m].as_str())
            .filter(|c| !c.is_empty())
    }

    /// The number of `quantity` for method column `m`, scaled; an error naming the file if it
    /// is missing or not a finite number (the table never shows a blank where the batch should
    /// have written a value).
    fn number(&self, quantity: &str, m: usize, scale: f64) -> Result<f64> {
        let file = self.path.display();
        let c = self
            .cell(quantity, m)
            .with_context(|| format!("{file}: no value of {quantity} (column {m})"))?;
        let v: f64 = c
            .parse()
            .with_context(|| format!("{file}: {quantity}: {c:?} is not a number"))?;
        if !v.is_finite() {
            bail!("{file}: {quantity}: {v} is not finite");
        }
        Ok(scale * v)
    }
}

/// The table's rows (header, separator, one row per case and method) from the summaries of
/// [`CASES`] in `results`.
fn table_rows(results: &Path) -> Result<Vec<String>> {
    let mut rows = vec![
        "| bearing | method | T_eff / T_out [°C] | μ_eff [mPa·s] | h_min, cycle min [µm] | ε max | side flow, mean [cm³/s] | power loss, mean [W] | peak pressure [MPa] | status |".to_string(),
        "|---|---|---|---|---|---|---|---|---|---|".to_string(),
    ];
    for case in CASES {
        let s = Summary::read(&results.join(format!("{case}_summary.csv")))?;
        for (m, method) in METHODS {
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
            rows.push(format!(
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
            ));
        }
    }
    Ok(rows)
}

/// When the summaries of `results` were last written, for the table's first line.
fn summaries_written(results: &Path) -> Result<String> {
    let mut written = None;
    for case in CASES {
        let path = results.join(format!("{case}_summary.csv"));
        let modified = std::fs::metadata(&path)
            .and_then(|m| m.modified())
            .with_context(|| format!("{} (run bash scripts/run_compressor.sh)", path.display()))?;
        written = written.max(Some(modified));
    }
    Ok(jiff::Timestamp::try_from(written.expect("two cases"))
        .context("summary file time")?
        .strftime("%Y-%m-%d %H:%M UTC")
        .to_string())
}

fn main() -> Result<()> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let write_docs = args.iter().any(|a| a == "--write-docs");
    let elastic = args.iter().any(|a| a == "--elastic");
    args.retain(|a| a != "--write-docs" && a != "--elastic");
    let results: PathBuf = match args.as_slice() {
        [] => Path::new(env!("CARGO_MANIFEST_DIR")).join("../results"),
        [flag, dir] if flag == "--results" => PathBuf::from(dir),
        other => bail!(
            "unexpected arguments {other:?} (expected --results DIR, --write-docs, --elastic)"
        ),
    };
    if elastic {
        return elastic_table(&results, write_docs);
    }
    let written = summaries_written(&results)?;
    let rows = table_rows(&results)?;
    report!(
        "Machine: {}. Summaries written: {written} by `bash scripts/run_compressor.sh` (release \
         build; both bearings in parallel, one core each). Deviations: mobility against rigorous.\n",
        machine(),
    );
    for row in rows {
        report!("{row}");
    }
    report!(
        "\nStep-to-step smoothness of the rigorous cycle (`jbearing_validation::smoothness`: \
         over the output steps of the periodic cycle, relative to each series' range; the drive \
         — load magnitude, feed pressure — sampled at the same steps for comparison):\n"
    );
    for row in smoothness_rows(&results)? {
        report!("{row}");
    }
    if write_docs {
        let page = docs_page("results.md");
        write_generated_block(&page, COMMAND, &take_report())
            .with_context(|| format!("writing the block into {}", page.display()))?;
        eprintln!("wrote the block of {COMMAND:?} in {}", page.display());
    }
    Ok(())
}

/// The smoothness table: per bearing the side leakage, the supply flow and the drive (|W|,
/// the feed pressure where it varies) of `results/CASE.h5`'s rigorous group, with the measures
/// of [`smoothness`] and the crank angles where they are largest.
fn smoothness_rows(results: &Path) -> Result<Vec<String>> {
    let mut rows = vec![
        "| bearing | series | largest second difference (crank) | zigzag amplitude (crank) | \
         sign changes of the step difference |"
            .to_string(),
        "|---|---|---:|---:|---:|".to_string(),
    ];
    for (case, label) in [("compressor_main", "main"), ("compressor_rod", "rod")] {
        let path = results.join(format!("{case}.h5"));
        let f = hdf5_metno::File::open(&path).with_context(|| format!("{}", path.display()))?;
        let g = f
            .group("rigorous")
            .with_context(|| format!("{}: no rigorous group", path.display()))?;
        let series = |name: &str| -> Result<Vec<f64>> {
            g.dataset(name)
                .and_then(|d| d.read_raw::<f64>())
                .with_context(|| format!("{}: rigorous/{name}", path.display()))
        };
        let crank = series("crank_angle")?;
        let (wx, wy) = (series("load_x")?, series("load_y")?);
        let load: Vec<f64> = wx.iter().zip(&wy).map(|(x, y)| x.hypot(*y)).collect();
        for (name, x) in [
            ("side leakage", series("side_leakage")?),
            ("supply flow", series("supply_flow")?),
            ("drive: load magnitude", load),
            ("drive: feed pressure", series("feed_pressure")?),
        ] {
            if x.len() != crank.len() {
                bail!(
                    "{}: rigorous/{name} has {} samples, crank_angle {}",
                    path.display(),
                    x.len(),
                    crank.len()
                );
            }
            let Some(s) = smoothness(&x) else {
                // A constant series (the main bearing's feed) has no measure.
                continue;
            };
            let pct = |v: f64| format!("{:.1} %", 100.0 * v);
            rows.push(format!(
                "| {label} | {name} | {} ({:.0}°) | {} | {} of {} |",
                pct(s.max_second_difference),
                crank[s.max_second_difference_at],
                if s.zigzag > 0.0 {
                    format!("{:.2} % ({:.0}°)", 100.0 * s.zigzag, crank[s.zigzag_at])
                } else {
                    "0".to_string()
                },
                s.sign_changes,
                x.len()
            ));
        }
    }
    Ok(rows)
}

/// The solver statistics of one run from its `CASE.h5`.
struct RunStats {
    wall_time: f64,
    cycles: i64,
    periodic: bool,
    stalled: i64,
    max_stalled_residual: f64,
    film_evaluations: i64,
    jacobian_evaluations: i64,
    started: String,
}

impl RunStats {
    fn read(path: &Path) -> Result<Self> {
        let f = hdf5_metno::File::open(path).with_context(|| format!("{}", path.display()))?;
        let g = f
            .group("rigorous")
            .with_context(|| format!("{}: no rigorous group", path.display()))?;
        let int = |name: &str| -> Result<i64> {
            g.attr(name)
                .and_then(|a| a.read_scalar::<i64>())
                .with_context(|| format!("{}: rigorous attribute {name}", path.display()))
        };
        let started = f
            .attr("started_utc")
            .and_then(|a| a.read_scalar::<hdf5_metno::types::VarLenUnicode>())
            .map(|s| s.as_str().to_string())
            .unwrap_or_default();
        Ok(Self {
            wall_time: f
                .attr("wall_time_s")
                .and_then(|a| a.read_scalar::<f64>())
                .with_context(|| format!("{}: wall_time_s", path.display()))?,
            cycles: int("cycles")?,
            periodic: g
                .attr("periodic")
                .and_then(|a| a.read_scalar::<i8>())
                .with_context(|| format!("{}: periodic", path.display()))?
                != 0,
            stalled: int("stalled_steps")?,
            max_stalled_residual: g
                .attr("max_stalled_residual")
                .and_then(|a| a.read_scalar::<f64>())
                .with_context(|| format!("{}: max_stalled_residual", path.display()))?,
            film_evaluations: int("film_evaluations")?,
            jacobian_evaluations: int("jacobian_evaluations")?,
            started,
        })
    }
}

/// The elastic compressor-rod table (module docs) into docs/validation.md with `write_docs`.
fn elastic_table(results: &Path, write_docs: bool) -> Result<()> {
    let (started, rows) = elastic_rows(results)?;
    report!(
        "Machine: {}. Runs (release build, `jbearing run`, one case at a time or several in parallel \
         on the shared machine, so the wall times are upper bounds) started: {}.\n",
        machine(),
        started.join("; "),
    );
    for row in rows {
        report!("{row}");
    }
    if write_docs {
        let page = docs_page("validation.md");
        write_generated_block(&page, ELASTIC_COMMAND, &take_report())
            .with_context(|| format!("writing the block into {}", page.display()))?;
        eprintln!(
            "wrote the block of {ELASTIC_COMMAND:?} in {}",
            page.display()
        );
    }
    Ok(())
}

/// The elastic table's runs ("label start time") and rows (header, separator, one row per run
/// of [`ELASTIC_CASES`] found in `results`); an error naming the file when a required run's
/// summary or HDF5 file is missing or lacks a value.
fn elastic_rows(results: &Path) -> Result<(Vec<String>, Vec<String>)> {
    let mut rows = Vec::new();
    for (case, label, required) in ELASTIC_CASES {
        let summary = results.join(format!("{case}_summary.csv"));
        let h5 = results.join(format!("{case}.h5"));
        if !(required || summary.exists() && h5.exists()) {
            continue;
        }
        rows.push((
            label,
            Summary::read(&summary)
                .with_context(|| format!("run cases/{case}.toml with jbearing run first"))?,
            RunStats::read(&h5)?,
        ));
    }
    let started: Vec<String> = rows
        .iter()
        .map(|(l, _, r)| format!("{l} {}", r.started))
        .collect();
    let mut table = vec![
        "| film | h_min, cycle min [µm] | ε max | power loss, mean [W] | side flow, mean [cm³/s] | cycles (periodic) | stalled steps (max residual / load) | film step evaluations | Jacobians | wall time per cycle | status |".to_string(),
        "|---|---|---|---|---|---|---|---|---|---|---|".to_string(),
    ];
    let rigid_hmin = rows[0].1.number("min_film_thickness_min", 0, 1e6)?;
    for (i, (label, s, r)) in rows.iter().enumerate() {
        let hmin = s.number("min_film_thickness_min", 0, 1e6)?;
        let hmin = if i == 0 {
            fixed(hmin, 3)
        } else {
            format!(
                "{} ({} %)",
                fixed(hmin, 3),
                signed(100.0 * (hmin / rigid_hmin - 1.0), 1)
            )
        };
        let stalled = if r.stalled == 0 {
            "0".to_string()
        } else {
            format!(
                "{} ({})",
                r.stalled,
                jbearing_validation::generated_docs::sci(r.max_stalled_residual, 1)
            )
        };
        table.push(format!(
            "| {label} | {hmin} | {} | {} | {} | {} ({}) | {stalled} | {} | {} | {} s | {} |",
            fixed(s.number("eccentricity_ratio_max", 0, 1.0)?, 4),
            fixed(s.number("power_loss_mean", 0, 1.0)?, 2),
            fixed(s.number("side_leakage_mean", 0, 1e6)?, 4),
            r.cycles,
            if r.periodic { "yes" } else { "no" },
            r.film_evaluations,
            r.jacobian_evaluations,
            fixed(r.wall_time / r.cycles.max(1) as f64, 1),
            s.cell("status", 0).unwrap_or("not run"),
        ));
    }
    Ok((started, table))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh directory under the system's temporary directory, removed when dropped.
    struct TempDir(PathBuf);

    impl TempDir {
        fn new(name: &str) -> Self {
            let dir = std::env::temp_dir().join(format!(
                "jbearing-results-table-{name}-{}",
                std::process::id()
            ));
            let _ = std::fs::remove_dir_all(&dir);
            std::fs::create_dir_all(&dir).unwrap();
            Self(dir)
        }
    }

    impl Drop for TempDir {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    /// A summary in the format of the application's `CsvSummaryWriter` (status first, then one
    /// row per quantity in SI units; the long names quoted as the csv crate writes them when
    /// they hold a comma).
    fn summary(rigorous_h: &str, mobility_status: &str) -> String {
        format!(
            "quantity,units,long_name,rigorous,mobility,mobility_deviation_percent\n\
             status,,\"ok, or what to know before trusting the method's numbers\",ok,{mobility_status},\n\
             effective_temperature,degC,effective film temperature,87.26,87.26,\n\
             outlet_temperature,degC,outlet temperature,95.04,95.04,\n\
             effective_viscosity,Pa s,effective viscosity,0.00981,0.00981,\n\
             min_film_thickness_min,m,cycle minimum of the minimum film thickness,{rigorous_h},1.5e-6,25.0\n\
             eccentricity_ratio_max,1,cycle maximum of the eccentricity ratio,0.8504,0.83,\n\
             side_leakage_mean,m3/s,cycle mean of the side leakage,6.3183e-6,5.9e-6,-6.62\n\
             power_loss_mean,W,cycle mean of the power loss,56.3,50.12,-10.98\n\
             max_pressure_max,Pa,cycle maximum of the peak pressure,1.2345e8,9.9e7,-19.8\n"
        )
    }

    #[test]
    fn rows_carry_the_summaries_values_in_the_tables_units() {
        let dir = TempDir::new("rows");
        std::fs::write(
            dir.0.join("compressor_main_summary.csv"),
            summary("1.2e-6", "ok"),
        )
        .unwrap();
        std::fs::write(
            dir.0.join("compressor_rod_summary.csv"),
            summary("3.8294e-6", "not periodic"),
        )
        .unwrap();
        let rows = table_rows(&dir.0).unwrap();
        assert_eq!(rows.len(), 2 + 4, "{rows:#?}");
        assert!(rows[0].starts_with("| bearing | method |"));
        // Values converted by hand from the SI cells above: °C as written, Pa s → mPa·s,
        // m → µm, m³/s → cm³/s, Pa → MPa; deviations on the mobility rows only.
        assert_eq!(
            rows[2],
            "| compressor_main | rigorous (JFO, inverse) | 87.3 / 95.0 | 9.8 | 1.20 | 0.850 | 6.318 | 56.3 | 123.45 | ok |"
        );
        assert_eq!(
            rows[3],
            "| compressor_main | mobility (finite-length map) | 87.3 / 95.0 | 9.8 | 1.50 (+25.0 %) | 0.830 | 5.900 (−6.6 %) | 50.1 (−11.0 %) | 99.00 (−19.8 %) | ok |"
        );
        assert_eq!(
            rows[4],
            "| compressor_rod | rigorous (JFO, inverse) | 87.3 / 95.0 | 9.8 | 3.83 | 0.850 | 6.318 | 56.3 | 123.45 | ok |"
        );
        assert!(rows[5].ends_with("| not periodic |"), "{}", rows[5]);
    }

    /// A run's `CASE.h5` as far as the elastic table reads it: the file's `wall_time_s` and
    /// `started_utc`, the rigorous group's statistics attributes (the types the application
    /// writes: integers i64, flags i8).
    fn run_h5(path: &Path, wall_time: f64, stats: [i64; 4], periodic: bool, max_stalled: f64) {
        use hdf5_metno::types::VarLenUnicode;
        let f = hdf5_metno::File::create(path).unwrap();
        f.new_attr::<f64>()
            .shape(())
            .create("wall_time_s")
            .unwrap()
            .write_scalar(&wall_time)
            .unwrap();
        let started: VarLenUnicode = "2026-11-27T01:00:00Z".parse().unwrap();
        f.new_attr::<VarLenUnicode>()
            .shape(())
            .create("started_utc")
            .unwrap()
            .write_scalar(&started)
            .unwrap();
        let g = f.create_group("rigorous").unwrap();
        let names = [
            "cycles",
            "stalled_steps",
            "film_evaluations",
            "jacobian_evaluations",
        ];
        for (name, v) in names.iter().zip(stats) {
            g.new_attr::<i64>()
                .shape(())
                .create(*name)
                .unwrap()
                .write_scalar(&v)
                .unwrap();
        }
        g.new_attr::<i8>()
            .shape(())
            .create("periodic")
            .unwrap()
            .write_scalar(&i8::from(periodic))
            .unwrap();
        g.new_attr::<f64>()
            .shape(())
            .create("max_stalled_residual")
            .unwrap()
            .write_scalar(&max_stalled)
            .unwrap();
    }

    /// The rigid rod run's summary and CASE.h5 statistics in `dir`: h_min 3.821 µm, 166.8 s
    /// over 12 cycles, 0 stalls, 12 782 film steps, 1 567 Jacobians, periodic.
    fn write_rigid_run(dir: &Path) {
        let rigid = ELASTIC_CASES[0].0;
        std::fs::write(
            dir.join(format!("{rigid}_summary.csv")),
            summary("3.821e-6", "ok"),
        )
        .unwrap();
        run_h5(
            &dir.join(format!("{rigid}.h5")),
            166.8,
            [12, 0, 12782, 1567],
            true,
            0.0,
        );
    }

    #[test]
    fn elastic_rows_carry_the_summaries_and_the_run_statistics() {
        let dir = TempDir::new("elastic");
        let elastic = ELASTIC_CASES[1].0;
        write_rigid_run(&dir.0);
        std::fs::write(
            dir.0.join(format!("{elastic}_summary.csv")),
            summary("4.0102e-6", "ok"),
        )
        .unwrap();
        run_h5(
            &dir.0.join(format!("{elastic}.h5")),
            901.2,
            [12, 65, 16526, 4997],
            false,
            7.24e-6,
        );
        let (started, rows) = elastic_rows(&dir.0).unwrap();
        // The optional looser-gap run has no files here: two rows.
        assert_eq!(rows.len(), 2 + 2, "{rows:#?}");
        assert_eq!(started.len(), 2);
        assert!(
            started[0].ends_with(" 2026-11-27T01:00:00Z"),
            "{}",
            started[0]
        );
        assert!(rows[0].starts_with("| film |"));
        // By hand: h_min m → µm, the elastic row's change against the rigid one
        // (4.0102 / 3.821 − 1 = +4.95 % → +5.0 % at one decimal), wall time per cycle 166.8 / 12 = 13.9 s and
        // 901.2 / 12 = 75.1 s, the stall count with its largest residual.
        assert_eq!(
            rows[2],
            format!(
                "| {} | 3.821 | 0.8504 | 56.30 | 6.3183 | 12 (yes) | 0 | 12782 | 1567 | 13.9 s | ok |",
                ELASTIC_CASES[0].1
            )
        );
        assert_eq!(
            rows[3],
            format!(
                "| {} | 4.010 (+5.0 %) | 0.8504 | 56.30 | 6.3183 | 12 (no) | 65 (7.2e-6) | 16526 | 4997 | 75.1 s | ok |",
                ELASTIC_CASES[1].1
            )
        );
    }

    #[test]
    fn a_missing_elastic_run_is_an_error_naming_the_file() {
        let dir = TempDir::new("elastic-missing");
        let elastic = ELASTIC_CASES[1].0;
        write_rigid_run(&dir.0);
        // The elastic run's summary is missing.
        let err = format!("{:#}", elastic_rows(&dir.0).unwrap_err());
        assert!(
            err.contains(&format!("{elastic}_summary.csv"))
                && err.contains(&format!("run cases/{elastic}.toml")),
            "{err}"
        );
        // Its summary is there but not its HDF5 file.
        std::fs::write(
            dir.0.join(format!("{elastic}_summary.csv")),
            summary("4.0102e-6", "ok"),
        )
        .unwrap();
        let err = format!("{:#}", elastic_rows(&dir.0).unwrap_err());
        assert!(err.contains(&format!("{elastic}.h5")), "{err}");
        // An HDF5 file without the statistics the table needs.
        let f = hdf5_metno::File::create(dir.0.join(format!("{elastic}.h5"))).unwrap();
        f.create_group("rigorous").unwrap();
        drop(f);
        let err = format!("{:#}", elastic_rows(&dir.0).unwrap_err());
        assert!(
            err.contains(&format!("{elastic}.h5")) && err.contains("wall_time_s"),
            "{err}"
        );
    }

    #[test]
    fn a_missing_summary_is_an_error_naming_the_file() {
        let dir = TempDir::new("missing");
        std::fs::write(
            dir.0.join("compressor_main_summary.csv"),
            summary("1.2e-6", "ok"),
        )
        .unwrap();
        let err = format!("{:#}", table_rows(&dir.0).unwrap_err());
        assert!(err.contains("compressor_rod_summary.csv"), "{err}");
        let err = format!("{:#}", summaries_written(&dir.0).unwrap_err());
        assert!(
            err.contains("compressor_rod_summary.csv") && err.contains("run_compressor.sh"),
            "{err}"
        );
    }

    #[test]
    fn a_malformed_summary_is_an_error_naming_the_file_and_the_value() {
        let dir = TempDir::new("malformed");
        std::fs::write(
            dir.0.join("compressor_main_summary.csv"),
            summary("1.2e-6", "ok"),
        )
        .unwrap();
        let rod = dir.0.join("compressor_rod_summary.csv");
        // A cell that is not a number.
        std::fs::write(&rod, summary("thin", "ok")).unwrap();
        let err = format!("{:#}", table_rows(&dir.0).unwrap_err());
        assert!(
            err.contains("compressor_rod_summary.csv")
                && err.contains("min_film_thickness_min")
                && err.contains("\"thin\" is not a number")
                && err.contains("compressor_rod, rigorous"),
            "{err}"
        );
        // A missing value (the batch left the cell empty).
        std::fs::write(&rod, summary("", "ok")).unwrap();
        let err = format!("{:#}", table_rows(&dir.0).unwrap_err());
        assert!(
            err.contains("compressor_rod_summary.csv")
                && err.contains("no value of min_film_thickness_min"),
            "{err}"
        );
        // A file without the method columns.
        std::fs::write(&rod, "quantity,units\nstatus,\n").unwrap();
        let err = format!("{:#}", table_rows(&dir.0).unwrap_err());
        assert!(
            err.contains("compressor_rod_summary.csv") && err.contains("no column \"rigorous\""),
            "{err}"
        );
    }
}
