//! Validation of jbearing: reference data with provenance (`data/reference/`) and the loaders
//! the validation tests in `tests/` use.

use std::path::Path;

/// Reads a numeric CSV from `data/reference/` (header line skipped): one `Vec<f64>` per row.
/// Panics with the file and row on a malformed entry (tests only).
pub fn read_reference_csv(name: &str) -> Vec<Vec<f64>> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/reference")
        .join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .enumerate()
        .map(|(row, l)| {
            l.split(',')
                .map(|v| {
                    v.trim()
                        .parse::<f64>()
                        .unwrap_or_else(|e| panic!("{name} row {row}: {v:?}: {e}"))
                })
                .collect()
        })
        .collect()
}
