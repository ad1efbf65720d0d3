//! Ritz tables T1–T5 of Antonić, Nikolić & Torović (\[Antonic2004\], §3 "Results"):
//! C_1 … C_4 per unit Λ for λ = r/l ∈ {0, 0.25, 0.5, 0.75, 1} and ε ∈ {0.7, 0.5, 0.3}, reproduced
//! with our assembly of eq. 12 ([`jbearing_solvers::ritz`]). Data and provenance:
//! `data/reference/ritz_antonic_tables.csv` / `.md`.
//!
//! Tolerance (the issue's): each coefficient within 0.5 % of the printed value or within
//! 1e-4 Λ absolute. The printed values have five significant digits (≤ 0.005 % rounding), so
//! a correct assembly lands far inside it; the test also reports the worst relative deviation.
//!
//! One row is a misprint and is checked as such (not skipped): T2 (λ = 0.25), ε = 0.3. Ours:
//! C = (0.95845, −0.25158, 0.053840, −0.0096059) Λ; printed (0.98678, −0.29797, 0.067668,
//! −0.012455) Λ, 3–30 % off. Why we call it a misprint rather than our error:
//! 1. the other 14 rows, including T2 at ε = 0.5 and 0.7 and all of T1, T3 at ε = 0.3, agree to
//!    ≤ 0.05 % with the same code;
//! 2. in every other (ε, coefficient) the printed |C_i| falls strictly as λ grows (T1 → T5), as
//!    it must (the λ² term adds stiffness); the printed T2 ε = 0.3 row breaks it (|C_4| = 0.012455
//!    exceeds T1's 0.012387), while our T2 row fits between T1 and T3;
//! 3. no other (ε, λ) reproduces the printed row either: the best on a grid ε ∈ [0.2, 0.6],
//!    λ ∈ [0, 1] is still > 2 % off, so it is not a row computed for a mislabelled ε or λ.

use jbearing_solvers::ritz::{RitzParams, solve_ritz};
use jbearing_validation::generated_docs::{minus, sig, write_if_requested};
use std::fmt::Write;
use std::path::Path;

/// The command that reproduces the table of docs/validation.md (its generated block's name).
const COMMAND: &str =
    "cargo test --release -p jbearing-validation --test ritz_tables -- --nocapture";

#[derive(Debug, serde::Deserialize)]
struct Row {
    table: String,
    lambda: f64,
    eccentricity_ratio: f64,
    c1: f64,
    c2: f64,
    c3: f64,
    c4: f64,
}

fn rows() -> Vec<Row> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/reference/ritz_antonic_tables.csv");
    let mut r = csv::Reader::from_path(&path).expect("ritz table csv");
    r.deserialize().map(|x| x.expect("row")).collect()
}

/// The misprinted row (see the module docs).
fn is_t2_misprint(row: &Row) -> bool {
    row.table == "T2" && row.eccentricity_ratio == 0.3
}

fn within(ours: f64, printed: f64) -> bool {
    (ours - printed).abs() <= (0.005 * printed.abs()).max(1e-4)
}

#[test]
fn ritz_tables_t1_to_t5() {
    let rows = rows();
    assert_eq!(rows.len(), 15, "five tables of three rows");
    let mut worst: f64 = 0.0;
    let mut failed = Vec::new();
    let mut table = String::from(
        "| table | λ | ε | C_1 ref / ours | C_2 ref / ours | C_3 ref / ours | C_4 ref / ours | worst error |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    for row in &rows {
        let s = solve_ritz(&RitzParams::new(row.eccentricity_ratio, row.lambda)).unwrap();
        let printed = [row.c1, row.c2, row.c3, row.c4];
        let ok = (0..4).all(|i| within(s.coefficients[i], printed[i]));
        let rel = (0..4)
            .map(|i| ((s.coefficients[i] - printed[i]) / printed[i]).abs())
            .fold(0.0, f64::max);
        println!(
            "{} λ={} ε={}: ours {:?} printed {:?} worst rel {:.3e}",
            row.table, row.lambda, row.eccentricity_ratio, s.coefficients, printed, rel
        );
        let _ = write!(
            table,
            "| {} | {} | {} |",
            row.table, row.lambda, row.eccentricity_ratio
        );
        for i in 0..4 {
            // The reference as the CSV prints it, ours to six significant digits.
            let printed = minus(&printed[i].to_string());
            let _ = write!(table, " {printed} / {} |", sig(s.coefficients[i], 6));
        }
        if is_t2_misprint(row) {
            let _ = writeln!(table, " **{:.0} % (misprint)** |", 100.0 * rel);
        } else {
            let _ = writeln!(table, " {:.3} % |", 100.0 * rel);
        }
        if is_t2_misprint(row) {
            assert!(!ok && rel > 0.2, "the T2 ε = 0.3 row now agrees: rel {rel}");
        } else if ok {
            worst = worst.max(rel);
        } else {
            failed.push((row.table.clone(), row.eccentricity_ratio, rel));
        }
    }
    println!("worst relative deviation of the 14 reproduced rows: {worst:.3e}");
    assert!(failed.is_empty(), "rows not reproduced: {failed:?}");
    // The observed worst is 4.3e-4 (T3, ε = 0.7); the printed digits alone allow ~5e-5, the rest
    // is the paper's own quadrature/solver. Guard the margin to the 0.5 % criterion.
    assert!(worst < 1e-3, "worst {worst}");
    print!("{table}");
    write_if_requested("validation.md", COMMAND, &table).expect("docs/validation.md block");
}

#[test]
fn the_t2_misprint_breaks_the_monotone_trend_in_lambda_and_matches_no_other_parameters() {
    let rows = rows();
    let get = |t: &str, e: f64| {
        rows.iter()
            .find(|r| r.table == t && r.eccentricity_ratio == e)
            .map(|r| [r.c1, r.c2, r.c3, r.c4])
            .unwrap()
    };
    let tables = ["T1", "T2", "T3", "T4", "T5"];
    for e in [0.3, 0.5, 0.7] {
        for w in tables.windows(2) {
            let (a, b) = (get(w[0], e), get(w[1], e));
            for i in 0..4 {
                let falls = b[i].abs() < a[i].abs();
                let misprint_involved = e == 0.3 && (w[0] == "T2" || w[1] == "T2");
                if !misprint_involved {
                    assert!(
                        falls,
                        "printed |C{}| rises from {} to {} at ε = {e}",
                        i + 1,
                        w[0],
                        w[1]
                    );
                }
            }
        }
    }
    // The misprinted row: |C_4| printed in T2 exceeds T1's at ε = 0.3.
    assert!(get("T2", 0.3)[3].abs() > get("T1", 0.3)[3].abs());
    // Ours falls monotonically through T1 → T2 → T3 at ε = 0.3.
    let ours = |l: f64| solve_ritz(&RitzParams::new(0.3, l)).unwrap().coefficients;
    let (c1, c2, c3) = (ours(0.0), ours(0.25), ours(0.5));
    for i in 0..4 {
        assert!(c2[i].abs() < c1[i].abs() && c3[i].abs() < c2[i].abs());
    }
    // No (ε, λ) on a grid reproduces the printed row to better than 2 %.
    let target = get("T2", 0.3);
    let mut best = f64::INFINITY;
    for ie in 0..=80 {
        let e = 0.2 + 0.005 * ie as f64;
        for il in 0..=100 {
            let l = 0.01 * il as f64;
            let c = solve_ritz(&RitzParams::new(e, l)).unwrap().coefficients;
            let d = (0..4)
                .map(|i| ((c[i] - target[i]) / target[i]).abs())
                .fold(0.0, f64::max);
            best = best.min(d);
        }
    }
    println!("best grid match of the printed T2 ε = 0.3 row: {best:.3e}");
    assert!(best > 0.02, "best {best}");
}
