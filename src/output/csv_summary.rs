//! The summary table of one case as CSV, one row per quantity:
//!
//! ```text
//! quantity,units,long_name,rigorous,mobility,mobility_deviation_percent
//! status,,"ok, or what to know before trusting the method's numbers",not periodic,ok,
//! min_film_thickness_min,m,cycle minimum of the minimum film thickness,1.2e-6,1.5e-6,25.0
//! ```
//!
//! The first row, `status`, holds each method's status instead of a number: `ok`, `not
//! periodic`, `N stalled`, `failed: …` (empty if the case did not ask for the method); read the
//! numbers with e.g. `pd.read_csv(f, index_col=0).drop("status")`.
//! Empty cells where a method did not compute a value. Numbers are written with Rust's shortest
//! round-trip formatting, so reading them back gives the same f64.

use std::path::{Path, PathBuf};

use super::{CaseReport, Method, OutputError, OutputWriter, write_atomically};

/// Writes `CASE_summary.csv`.
#[derive(Debug, Clone, Copy, Default)]
pub struct CsvSummaryWriter;

impl CsvSummaryWriter {
    /// Path of the file written for `report` in `dir`.
    pub fn file_path(report: &CaseReport, dir: &Path) -> PathBuf {
        dir.join(format!("{}_summary.csv", report.case_name))
    }
}

fn cell(v: Option<f64>) -> String {
    v.map(|x| x.to_string()).unwrap_or_default()
}

impl OutputWriter for CsvSummaryWriter {
    fn name(&self) -> &'static str {
        "csv-summary"
    }

    fn write(&self, report: &CaseReport, dir: &Path) -> Result<Vec<PathBuf>, OutputError> {
        report.validate()?;
        let path = Self::file_path(report, dir);
        write_atomically(&path, |tmp| {
            let csv_err = |source| OutputError::Csv {
                path: path.clone(),
                source,
            };
            let mut w = csv::Writer::from_path(tmp).map_err(csv_err)?;
            w.write_record([
                "quantity",
                "units",
                "long_name",
                "rigorous",
                "mobility",
                "mobility_deviation_percent",
            ])
            .map_err(csv_err)?;
            // First row: each method's status ("ok", "not periodic", "3 stalled",
            // "failed: …"), so that the numbers below are never read without it.
            let status = |m| report.status(m).unwrap_or_default();
            w.write_record([
                "status".to_string(),
                String::new(),
                "ok, or what to know before trusting the method's numbers".into(),
                status(Method::Rigorous),
                status(Method::Mobility),
                String::new(),
            ])
            .map_err(csv_err)?;
            for r in &report.summary {
                w.write_record([
                    r.name.clone(),
                    r.units.clone(),
                    r.long_name.clone(),
                    cell(r.rigorous),
                    cell(r.mobility),
                    cell(r.mobility_deviation().map(|d| 100.0 * d)),
                ])
                .map_err(csv_err)?;
            }
            w.flush().map_err(|source| OutputError::Io {
                action: "flushing",
                path: path.clone(),
                source,
            })
        })?;
        Ok(vec![path])
    }
}
