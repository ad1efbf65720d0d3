//! Fuzzing the case parser and its CSV tables (proptest): valid case files and tables, mutated
//! at random — lines deleted, duplicated or replaced by random text, numbers replaced by
//! extreme or malformed ones, the text cut short, bytes inserted — must never panic or hang,
//! and every rejection must name its file with a line number ≥ 1 (the case file, or the CSV
//! file) — issue 12. Each mutated input is parsed and then priced by the budget (which must not
//! panic either).
//!
//! Bounded for CI: 400 cases per property by default (`PROPTEST_CASES` raises it for a long
//! run, e.g. `PROPTEST_CASES=100000 cargo test --release --test fuzz_case_files`). A single
//! parse taking longer than 10 s counts as a hang (a parse takes about a millisecond).

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use jbearing::budget::{Limits, check};
use jbearing::case::Case;
use proptest::prelude::*;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn config() -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(400);
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// One edit of a text, by line.
#[derive(Debug, Clone)]
enum Mutation {
    Delete(usize),
    Duplicate(usize),
    Replace(usize, String),
    /// Replace the first number on the line by this text.
    Number(usize, String),
    Truncate(usize),
    Insert(usize, String),
}

fn junk() -> impl Strategy<Value = String> {
    prop_oneof![
        // TOML and CSV punctuation, digits, letters, quotes, comments.
        "[a-z_.=\\[\\]\"',#0-9 eE+-]{0,40}",
        // Anything printable, including non-ASCII and control characters.
        any::<String>().prop_map(|s| s.chars().take(40).collect()),
        Just("\u{feff}".to_string()),
        Just("\"unterminated".to_string()),
        Just("[[grooves]]".to_string()),
        Just("[solver]\nmax_cycles = 0".to_string()),
    ]
}

fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("-inf".to_string()),
        Just("-1".to_string()),
        Just("0".to_string()),
        Just("1e308".to_string()),
        Just("1e-308".to_string()),
        Just("18446744073709551616".to_string()),
        Just("\"12\"".to_string()),
        Just("1,5".to_string()),
        any::<f64>().prop_map(|v| format!("{v:e}")),
        any::<i64>().prop_map(|v| v.to_string()),
    ]
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let at = 0usize..400;
    prop_oneof![
        at.clone().prop_map(Mutation::Delete),
        at.clone().prop_map(Mutation::Duplicate),
        (at.clone(), junk()).prop_map(|(i, s)| Mutation::Replace(i, s)),
        (at.clone(), number()).prop_map(|(i, s)| Mutation::Number(i, s)),
        (0usize..20_000).prop_map(Mutation::Truncate),
        (at, junk()).prop_map(|(i, s)| Mutation::Insert(i, s)),
    ]
}

fn apply(text: &str, mutations: &[Mutation]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for m in mutations {
        let n = lines.len().max(1);
        match m {
            Mutation::Delete(i) if !lines.is_empty() => {
                lines.remove(i % n);
            }
            Mutation::Duplicate(i) if !lines.is_empty() => {
                let l = lines[i % n].clone();
                lines.insert(i % n, l);
            }
            Mutation::Replace(i, s) if !lines.is_empty() => lines[i % n] = s.clone(),
            Mutation::Number(i, s) if !lines.is_empty() => {
                let l = &lines[i % n];
                if let Some(start) = l.find(|c: char| c.is_ascii_digit()) {
                    let end = l[start..]
                        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '.' || c == '-'))
                        .map_or(l.len(), |e| start + e);
                    lines[i % n] = format!("{}{s}{}", &l[..start], &l[end..]);
                }
            }
            Mutation::Truncate(k) => {
                let joined = lines.join("\n");
                let mut cut = (*k).min(joined.len());
                while !joined.is_char_boundary(cut) {
                    cut -= 1;
                }
                lines = joined[..cut].lines().map(str::to_string).collect();
            }
            Mutation::Insert(i, s) => lines.insert(i % n.max(1) % (lines.len() + 1), s.clone()),
            _ => {}
        }
    }
    lines.join("\n")
}

/// Parse `case_text` as `dir/case.toml` with `csv_text` as its `compressor_main_load.csv`;
/// check the outcome's invariants.
fn parse_and_check(dir: &Path, case_text: &str, csv_text: &str) -> Result<(), TestCaseError> {
    let case_path = dir.join("case.toml");
    let csv_path = dir.join("compressor_main_load.csv");
    std::fs::write(&csv_path, csv_text).expect("write the table");
    let started = Instant::now();
    let result = std::panic::catch_unwind(|| {
        let case = Case::from_text(case_text, &case_path);
        if let Ok(c) = &case {
            let _ = check(c, &Limits::default());
        }
        case.map(|_| ()).map_err(|e| e.to_string())
    });
    prop_assert!(
        started.elapsed() < Duration::from_secs(10),
        "a parse took {:?}",
        started.elapsed()
    );
    let outcome = match result {
        Ok(outcome) => outcome,
        Err(_) => return Err(TestCaseError::fail("the parser panicked")),
    };
    if let Err(message) = outcome {
        let named = [&case_path, &csv_path].iter().any(|p| {
            message
                .strip_prefix(&format!("{}:", p.display()))
                .is_some_and(|rest| rest.starts_with(|c: char| c.is_ascii_digit() && c != '0'))
        });
        prop_assert!(named, "the rejection names no file and line: {message}");
    }
    Ok(())
}

fn originals() -> (String, String) {
    let case = std::fs::read_to_string(root().join("cases/compressor_main.toml")).unwrap();
    // A short table keeps each case fast; its last angle stays below one cycle.
    let csv: String = std::fs::read_to_string(root().join("cases/compressor_main_load.csv"))
        .unwrap()
        .lines()
        .take(40)
        .map(|l| format!("{l}\n"))
        .collect();
    (case, csv)
}

#[test]
fn the_originals_parse() {
    let dir = tempfile::tempdir().unwrap();
    let (case, csv) = originals();
    std::fs::write(dir.path().join("compressor_main_load.csv"), &csv).unwrap();
    Case::from_text(&case, &dir.path().join("case.toml")).expect("the unmutated case is valid");
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn mutated_case_files_never_panic_and_name_file_and_line(
        mutations in proptest::collection::vec(mutation(), 1..4)
    ) {
        let dir = tempfile::tempdir().unwrap();
        let (case, csv) = originals();
        parse_and_check(dir.path(), &apply(&case, &mutations), &csv)?;
    }

    #[test]
    fn mutated_csv_tables_never_panic_and_name_file_and_line(
        mutations in proptest::collection::vec(mutation(), 1..4)
    ) {
        let dir = tempfile::tempdir().unwrap();
        let (case, csv) = originals();
        parse_and_check(dir.path(), &case, &apply(&csv, &mutations))?;
    }

    #[test]
    fn random_bytes_as_a_table_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
        let dir = tempfile::tempdir().unwrap();
        let (case, _) = originals();
        let csv_path = dir.path().join("compressor_main_load.csv");
        std::fs::write(&csv_path, &bytes).unwrap();
        let case_path = dir.path().join("case.toml");
        let r = std::panic::catch_unwind(|| Case::from_text(&case, &case_path).map(|_| ()));
        prop_assert!(r.is_ok(), "the parser panicked");
    }
}
