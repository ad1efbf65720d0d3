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

/// The example of Flores et al. \[Flores2006\] (§5 and Table 1): L = 25.4 mm, D = 63.5 mm,
/// c = 35.56 µm (the table's "mm" is a unit slip), μ = 4.16 cP, 2000 rpm, fixed bearing, the
/// Bouldin & Berker engine load of `data/reference/flores2006_load.csv` (720° cycle, along −Y),
/// start ε⁰ = 0.1 at φ⁰ = 1.5 rad.
pub mod flores2006 {
    use jbearing_solvers::mobility::{
        LoadInterpolation, MobilityParams, OrbitParams, TabulatedLoad,
    };
    use std::f64::consts::TAU;

    /// Crank (= journal) speed, rad/s.
    pub fn omega() -> f64 {
        2000.0 * TAU / 60.0
    }

    /// The bearing of Table 1.
    pub fn bearing() -> MobilityParams {
        MobilityParams {
            radius: 0.5 * 63.5e-3,
            length: 25.4e-3,
            radial_clearance: 35.56e-6,
            viscosity: 4.16e-3,
            omega_journal: omega(),
            omega_bearing: 0.0,
        }
    }

    /// The load of Fig. 6 (kN in the file), linear between the digitised points.
    pub fn load() -> TabulatedLoad {
        let rows = super::read_reference_csv("flores2006_load.csv");
        let angle: Vec<f64> = rows.iter().map(|r| r[0]).collect();
        let force: Vec<f64> = rows.iter().map(|r| r[1] * 1e3).collect();
        TabulatedLoad::unidirectional(
            angle,
            &force,
            [0.0, -1.0],
            720.0,
            omega(),
            LoadInterpolation::Linear,
        )
        .expect("flores2006_load.csv is a valid load table")
    }

    /// Orbit parameters with the paper's start.
    pub fn orbit_params() -> OrbitParams {
        let mut p = OrbitParams::new(bearing());
        p.initial_eccentricity = [0.1 * 1.5f64.sin(), -0.1 * 1.5f64.cos()];
        p
    }
}

/// The compressor main bearing of Yu & Sawicki \[YuSawicki2002\] Table II (docs/conventions.md §7) as used by the
/// inverse-solver tests and the inverse timing report: L = 18.288 mm, R = 27.43 mm,
/// c = 48.9 µm, a partial groove 24.9 × 3.81 mm at θ = 90° (top, unloaded side) fed at
/// 0.2068 MPa, 1800 rpm; μ = 0.02 Pa·s assumed. The synthetic compressor-like load: a 4 kN
/// pulse once per turn on 0.8 kN, plus a 0.6 kN second-order side load.
pub mod compressor_main {
    use jbearing_solvers::reynolds::{GridParams, Groove, ReynoldsParams, TimeScheme};
    use std::f64::consts::{PI, TAU};

    /// Crank (= journal) speed, rad/s.
    pub const OMEGA: f64 = 1800.0 * TAU / 60.0;
    /// Groove feed pressure (gauge), Pa.
    pub const FEED: f64 = 0.2068e6;

    /// The Reynolds-solver parameters on an n_θ × n_z grid with the given time scheme.
    pub fn reynolds_params(scheme: TimeScheme, n_theta: usize, n_z: usize) -> ReynoldsParams {
        let mut p = ReynoldsParams::plain(27.43e-3, 18.288e-3, 48.9e-6, 0.02);
        p.grid = GridParams { n_theta, n_z };
        p.time_scheme = scheme;
        p.grooves = vec![Groove {
            center_angle: 0.5 * PI,
            center_z: 0.0,
            angular_width: 24.9e-3 / 27.43e-3,
            axial_width: 3.81e-3,
            cutoff_film_fraction: 0.01,
        }];
        p
    }

    /// The synthetic load (N, bearing frame) at time t.
    pub fn pulse_load(t: f64) -> [f64; 2] {
        let a = OMEGA * t;
        [
            600.0 * (2.0 * a).sin(),
            -800.0 - 4000.0 * (0.5 * (1.0 - a.cos())).powi(4),
        ]
    }
}

/// Generated tables in the markdown docs: a table that a command measures sits in a page
/// between `<!-- BEGIN generated: COMMAND -->` and `<!-- END generated -->`, and the command,
/// run with `--write-docs`, replaces what lies between them with its fresh output
/// ([`write_generated_block`](generated_docs::write_generated_block)). Everything outside the
/// block — the prose around it, other commands' blocks — is left byte for byte.
pub mod generated_docs {
    use std::io::Write;
    use std::path::{Path, PathBuf};

    /// The line that opens the block of `command`.
    pub fn begin_marker(command: &str) -> String {
        format!("<!-- BEGIN generated: {command} -->")
    }

    /// The line that closes every block.
    pub const END_MARKER: &str = "<!-- END generated -->";

    /// Why a generated block could not be replaced; the page is then left unchanged.
    #[derive(Debug, thiserror::Error)]
    pub enum GeneratedDocsError {
        /// The page has no `<!-- BEGIN generated: COMMAND -->` line for this command.
        #[error(
            "{path}: no line {marker:?}; the blocks of this page belong to: {found}",
            marker = begin_marker(command),
            found = if found.is_empty() { "(none)".to_string() } else { found.join("; ") }
        )]
        MissingBegin {
            path: PathBuf,
            command: String,
            found: Vec<String>,
        },
        /// The page has more than one block of this command.
        #[error("{path}: {count} blocks of {command:?} (lines {lines:?}); expected one")]
        DuplicateBegin {
            path: PathBuf,
            command: String,
            count: usize,
            lines: Vec<usize>,
        },
        /// The block opened at `begin_line` is not closed by `<!-- END generated -->` before the
        /// next block opens or the page ends.
        #[error("{path}:{begin_line}: the block of {command:?} has no {END_MARKER:?} line")]
        MissingEnd {
            path: PathBuf,
            command: String,
            begin_line: usize,
        },
        /// Reading the page or writing its new version failed.
        #[error("{path}: {source}")]
        Io {
            path: PathBuf,
            source: std::io::Error,
        },
    }

    /// `text` with the block of `command` replaced by `content` (a trailing newline is added if
    /// it lacks one). `path` only names the page in errors.
    pub fn replace_generated_block(
        path: &Path,
        text: &str,
        command: &str,
        content: &str,
    ) -> Result<String, GeneratedDocsError> {
        let marker = begin_marker(command);
        // Byte offsets of line starts, to splice without touching any other byte.
        let mut starts = vec![0usize];
        starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        let lines: Vec<&str> = text.split_inclusive('\n').collect();
        let begins: Vec<usize> = lines
            .iter()
            .enumerate()
            .filter(|(_, l)| l.trim() == marker)
            .map(|(i, _)| i)
            .collect();
        let begin = match begins.as_slice() {
            [] => {
                let found = lines
                    .iter()
                    .filter_map(|l| l.trim().strip_prefix("<!-- BEGIN generated:"))
                    .map(|r| r.trim_end_matches("-->").trim().to_string())
                    .collect();
                return Err(GeneratedDocsError::MissingBegin {
                    path: path.to_path_buf(),
                    command: command.to_string(),
                    found,
                });
            }
            [b] => *b,
            many => {
                return Err(GeneratedDocsError::DuplicateBegin {
                    path: path.to_path_buf(),
                    command: command.to_string(),
                    count: many.len(),
                    lines: many.iter().map(|b| b + 1).collect(),
                });
            }
        };
        let end = lines[begin + 1..]
            .iter()
            .position(|l| {
                let t = l.trim();
                t == END_MARKER || t.starts_with("<!-- BEGIN generated:")
            })
            .map(|k| begin + 1 + k)
            .filter(|&e| lines[e].trim() == END_MARKER)
            .ok_or_else(|| GeneratedDocsError::MissingEnd {
                path: path.to_path_buf(),
                command: command.to_string(),
                begin_line: begin + 1,
            })?;
        let mut out = String::with_capacity(text.len() + content.len());
        out.push_str(&text[..starts[begin + 1]]);
        // The BEGIN line may be the last line without a newline only if END follows it, which
        // cannot be: END comes after, so the BEGIN line ends with '\n'.
        out.push_str(content);
        if !content.is_empty() && !content.ends_with('\n') {
            out.push('\n');
        }
        out.push_str(&text[starts[end]..]);
        Ok(out)
    }

    /// Replaces the block of `command` in the page `path` by `content` and writes the page
    /// atomically: the new text goes to a hidden temporary file beside it, is flushed to disk and
    /// renamed over the page, so a reader sees the old page or the new one, never a mix; on any
    /// error the page is unchanged and the temporary file removed.
    pub fn write_generated_block(
        path: &Path,
        command: &str,
        content: &str,
    ) -> Result<(), GeneratedDocsError> {
        let io = |source| GeneratedDocsError::Io {
            path: path.to_path_buf(),
            source,
        };
        let text = std::fs::read_to_string(path).map_err(io)?;
        let new = replace_generated_block(path, &text, command, content)?;
        let dir = path
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let tmp = dir.join(format!(".{name}.generated-{}.tmp", std::process::id()));
        let written = (|| {
            let mut f = std::fs::File::create(&tmp)?;
            f.write_all(new.as_bytes())?;
            f.sync_all()?;
            std::fs::rename(&tmp, path)
        })();
        if let Err(e) = written {
            let _ = std::fs::remove_file(&tmp);
            return Err(io(e));
        }
        Ok(())
    }

    static REPORT: std::sync::Mutex<String> = std::sync::Mutex::new(String::new());

    /// Prints `text` to stdout and keeps it for [`take_report`]: what a report binary prints
    /// is what `--write-docs` writes. Use through [`report!`](crate::report) and
    /// [`report_part!`](crate::report_part).
    pub fn report_text(text: &str) {
        print!("{text}");
        REPORT
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
            .push_str(text);
    }

    /// Everything reported so far (and forgets it).
    pub fn take_report() -> String {
        std::mem::take(
            &mut *REPORT
                .lock()
                .unwrap_or_else(|poisoned| poisoned.into_inner()),
        )
    }

    /// The workspace's `docs/NAME` (from this crate's manifest directory), for `--write-docs`.
    pub fn docs_page(name: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../docs")
            .join(name)
    }

    #[cfg(test)]
    mod tests {
        use super::*;

        const PAGE: &str = "# Page\n\nprose before\n<!-- BEGIN generated: cmd a -->\nold a\nold a 2\n<!-- END generated -->\nprose between\n<!-- BEGIN generated: cmd b -->\nold b\n<!-- END generated -->\nprose after";

        #[test]
        fn replaces_only_its_own_block() {
            let out = replace_generated_block(Path::new("p.md"), PAGE, "cmd a", "new a").unwrap();
            let want = PAGE.replace("old a\nold a 2\n", "new a\n");
            assert_eq!(out, want);
            // The other block and every byte outside the block are untouched.
            assert!(out.contains("old b\n") && out.ends_with("prose after"));
            let out = replace_generated_block(Path::new("p.md"), PAGE, "cmd b", "new b\n").unwrap();
            assert_eq!(out, PAGE.replace("old b\n", "new b\n"));
            // An empty block stays empty; replacing twice gives the same page as once.
            let empty = replace_generated_block(Path::new("p.md"), PAGE, "cmd a", "").unwrap();
            assert_eq!(empty, PAGE.replace("old a\nold a 2\n", ""));
            let twice = replace_generated_block(Path::new("p.md"), &out, "cmd b", "new b").unwrap();
            assert_eq!(twice, out);
        }

        #[test]
        fn refuses_missing_duplicate_or_unclosed_markers() {
            let e = replace_generated_block(Path::new("p.md"), PAGE, "cmd c", "x").unwrap_err();
            match &e {
                GeneratedDocsError::MissingBegin { found, .. } => {
                    assert_eq!(found, &["cmd a", "cmd b"])
                }
                other => panic!("{other}"),
            }
            assert!(
                e.to_string().contains("<!-- BEGIN generated: cmd c -->"),
                "{e}"
            );
            // A command whose name is a prefix of another's is not mistaken for it.
            assert!(replace_generated_block(Path::new("p.md"), PAGE, "cmd", "x").is_err());
            let dup = format!("{PAGE}\n<!-- BEGIN generated: cmd a -->\n<!-- END generated -->\n");
            let e = replace_generated_block(Path::new("p.md"), &dup, "cmd a", "x").unwrap_err();
            assert!(
                matches!(&e, GeneratedDocsError::DuplicateBegin { count: 2, lines, .. } if lines == &[4, 13]),
                "{e}"
            );
            // END missing before the next block opens, and at the end of the page.
            let unclosed =
                PAGE.replacen("<!-- END generated -->\nprose between", "prose between", 1);
            let e =
                replace_generated_block(Path::new("p.md"), &unclosed, "cmd a", "x").unwrap_err();
            assert!(
                matches!(e, GeneratedDocsError::MissingEnd { begin_line: 4, .. }),
                "{e}"
            );
            let cut = "a\n<!-- BEGIN generated: cmd a -->\nrows\n";
            let e = replace_generated_block(Path::new("p.md"), cut, "cmd a", "x").unwrap_err();
            assert!(matches!(e, GeneratedDocsError::MissingEnd { .. }), "{e}");
        }

        #[test]
        fn writes_the_page_atomically_and_leaves_it_alone_on_refusal() {
            let dir = std::env::temp_dir()
                .join(format!("jbearing-generated-docs-{}", std::process::id()));
            std::fs::create_dir_all(&dir).unwrap();
            let page = dir.join("page.md");
            std::fs::write(&page, PAGE).unwrap();
            write_generated_block(&page, "cmd b", "| new | table |").unwrap();
            assert_eq!(
                std::fs::read_to_string(&page).unwrap(),
                PAGE.replace("old b\n", "| new | table |\n")
            );
            let before = std::fs::read_to_string(&page).unwrap();
            assert!(write_generated_block(&page, "cmd z", "x").is_err());
            assert_eq!(std::fs::read_to_string(&page).unwrap(), before);
            // No temporary file is left behind, after success or refusal.
            let left: Vec<_> = std::fs::read_dir(&dir)
                .unwrap()
                .map(|e| e.unwrap().file_name())
                .collect();
            assert_eq!(left, [std::ffi::OsString::from("page.md")]);
            let missing = dir.join("missing.md");
            assert!(matches!(
                write_generated_block(&missing, "cmd a", "x"),
                Err(GeneratedDocsError::Io { .. })
            ));
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }
}

/// `println!` that also keeps the line for `--write-docs` ([`generated_docs::take_report`]).
#[macro_export]
macro_rules! report {
    () => {
        $crate::generated_docs::report_text("\n")
    };
    ($($arg:tt)*) => {
        $crate::generated_docs::report_text(&format!("{}\n", format_args!($($arg)*)))
    };
}

/// `print!` that also keeps the text for `--write-docs` ([`generated_docs::take_report`]).
#[macro_export]
macro_rules! report_part {
    ($($arg:tt)*) => {
        $crate::generated_docs::report_text(&format!($($arg)*))
    };
}
