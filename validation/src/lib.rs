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
pub mod smoothness;

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
/// block — the prose around it, other commands' blocks — is left byte for byte. Validation tests
/// write their own tables the same way when run with `JBEARING_WRITE_DOCS=1`
/// ([`write_if_requested`](generated_docs::write_if_requested)), the block named by the
/// test's command.
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
    /// error the page is unchanged and the temporary file removed. Writes of one process are
    /// serialized (a process-wide lock) and the page is read inside the lock, so tests of one binary
    /// running in parallel, each writing its own block of one page, all keep their block.
    pub fn write_generated_block(
        path: &Path,
        command: &str,
        content: &str,
    ) -> Result<(), GeneratedDocsError> {
        let _guard = WRITE_LOCK
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
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

    /// Held from reading a page to renaming its new version over it: without it, two threads
    /// writing different blocks of one page would each write the page they read, and the later
    /// rename would drop the earlier block (and they would share the temporary file's name).
    static WRITE_LOCK: std::sync::Mutex<()> = std::sync::Mutex::new(());

    /// The environment variable that makes validation tests write their tables into the docs:
    /// `JBEARING_WRITE_DOCS=1 cargo test --release -p jbearing-validation --test NAME`. Unset (as
    /// in CI), the tests only print and assert.
    pub const WRITE_DOCS_VAR: &str = "JBEARING_WRITE_DOCS";

    /// Whether [`WRITE_DOCS_VAR`] asks for the docs to be written: set to `1`.
    pub fn write_docs_requested() -> bool {
        std::env::var(WRITE_DOCS_VAR).is_ok_and(|v| v.trim() == "1")
    }

    /// The first line of a block a validation test writes: the date, the build and the command
    /// (the marker that names it is an HTML comment, invisible on the rendered page) are what a
    /// reader needs to judge whether the numbers below are still current and to reproduce them.
    pub fn measured_line(command: &str) -> String {
        let profile = if cfg!(debug_assertions) {
            "dev build"
        } else {
            "release build"
        };
        format!(
            "Measured {} ({profile}) by `{command}`.\n",
            jiff::Timestamp::now().strftime("%Y-%m-%d %H:%M UTC")
        )
    }

    /// For a validation test: when [`write_docs_requested`], puts `text` (after
    /// [`measured_line`] and a blank line) into the block of `command` of `docs/PAGE`
    /// ([`docs_page`]) and returns `Ok(true)`; otherwise does nothing and returns `Ok(false)`.
    /// `command` is the exact command that reproduces the table.
    pub fn write_if_requested(
        page: &str,
        command: &str,
        text: &str,
    ) -> Result<bool, GeneratedDocsError> {
        write_if_requested_to(write_docs_requested(), &docs_page(page), command, text)
    }

    /// [`write_if_requested`] with the request and the page's path explicit (for tests).
    pub fn write_if_requested_to(
        requested: bool,
        path: &Path,
        command: &str,
        text: &str,
    ) -> Result<bool, GeneratedDocsError> {
        if !requested {
            return Ok(false);
        }
        let content = format!("{}\n{text}", measured_line(command));
        write_generated_block(path, command, &content)?;
        Ok(true)
    }

    /// "AMD EPYC, 2 logical CPUs" from /proc/cpuinfo: the machine line of a generated block.
    pub fn machine() -> String {
        let Ok(info) = std::fs::read_to_string("/proc/cpuinfo") else {
            return "unknown machine (no /proc/cpuinfo)".to_string();
        };
        let model = info
            .lines()
            .find_map(|l| {
                let (k, v) = l.split_once(':')?;
                (k.trim() == "model name").then(|| v.trim().to_string())
            })
            .unwrap_or_else(|| "unknown CPU".to_string());
        let cpus = info
            .lines()
            .filter(|l| l.split(':').next().is_some_and(|k| k.trim() == "processor"))
            .count();
        format!("{model}, {cpus} logical CPUs")
    }

    /// `x` with `digits` significant digits in fixed notation (never an exponent) and the
    /// typographic minus of the docs' tables (−); `NaN` and infinities as Rust prints them.
    pub fn sig(x: f64, digits: usize) -> String {
        if !x.is_finite() {
            return x.to_string();
        }
        if x == 0.0 {
            return "0".into();
        }
        let magnitude = x.abs().log10().floor() as i64;
        let decimals = (digits as i64 - 1 - magnitude).max(0) as usize;
        let mut s = format!("{x:.decimals$}");
        // Rounding may carry into a new digit (9.9996 → "10.000"): one decimal too many then.
        let significant = s.replace(['-', '.'], "");
        if decimals > 0 && significant.trim_start_matches('0').len() > digits {
            s = format!("{x:.prec$}", prec = decimals - 1);
        }
        minus(&s)
    }

    /// `x` with `decimals` decimals and the typographic minus (−).
    pub fn fixed(x: f64, decimals: usize) -> String {
        minus(&format!("{x:.decimals$}"))
    }

    /// `x` with an explicit sign and `decimals` decimals, typographic minus; a value that rounds
    /// to zero is written without a sign ("0.00", not "−0.00").
    pub fn signed(x: f64, decimals: usize) -> String {
        let s = format!("{x:+.decimals$}");
        if s[1..].chars().all(|c| c == '0' || c == '.') {
            return s[1..].to_string();
        }
        minus(&s)
    }

    /// `x` in scientific notation with `decimals` decimals ("−6e-8", "1.3e-13"), typographic
    /// minus on the mantissa; exactly zero (of either sign) is "0".
    pub fn sci(x: f64, decimals: usize) -> String {
        if x == 0.0 {
            return "0".into();
        }
        let s = format!("{:.decimals$e}", x.abs());
        if x < 0.0 { format!("−{s}") } else { s }
    }

    /// `s` with every ASCII hyphen-minus replaced by the typographic minus (−) of the docs.
    pub fn minus(s: &str) -> String {
        s.replace('-', "−")
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

        #[test]
        fn parallel_writers_of_one_page_keep_every_block() {
            let dir = std::env::temp_dir().join(format!(
                "jbearing-generated-parallel-{}",
                std::process::id()
            ));
            std::fs::create_dir_all(&dir).unwrap();
            let page = dir.join("page.md");
            let blocks: Vec<String> = (0..8)
                .map(|i| {
                    format!("<!-- BEGIN generated: cmd {i} -->\nold\n<!-- END generated -->\n")
                })
                .collect();
            std::fs::write(&page, format!("# Page\n{}tail\n", blocks.concat())).unwrap();
            // Eight threads, each rewriting its own block 20 times: without the lock the
            // read-modify-rename of one thread overwrites another's block (or two threads
            // share the temporary file), and some `new i` would be missing at the end.
            std::thread::scope(|s| {
                for i in 0..8 {
                    let page = &page;
                    s.spawn(move || {
                        for round in 0..20 {
                            let text = format!("| new {i} | round {round} |");
                            write_generated_block(page, &format!("cmd {i}"), &text).unwrap();
                        }
                    });
                }
            });
            let out = std::fs::read_to_string(&page).unwrap();
            for i in 0..8 {
                assert!(out.contains(&format!("| new {i} | round 19 |\n")), "{out}");
            }
            assert!(!out.contains("old") && out.ends_with("tail\n"), "{out}");
            std::fs::remove_dir_all(&dir).unwrap();
        }

        #[test]
        fn numbers_in_the_docs_style() {
            assert_eq!(sig(3.752_284, 6), "3.75228");
            assert_eq!(sig(-0.009_605_901, 6), "−0.00960590");
            assert_eq!(sig(-0.311_768_4, 6), "−0.311768");
            assert_eq!(sig(9.999_96, 4), "10.00");
            assert_eq!(sig(0.099_996, 3), "0.100");
            assert_eq!(sig(31.275, 6), "31.2750");
            assert_eq!(sig(123_456.7, 3), "123457");
            assert_eq!(sig(0.0, 3), "0");
            assert_eq!(fixed(-6e-8, 1), "−0.0");
            assert_eq!(fixed(2.345, 1), "2.3");
            assert_eq!(signed(-0.004, 2), "0.00");
            assert_eq!(signed(0.28, 2), "+0.28");
            assert_eq!(signed(-10.3, 1), "−10.3");
            assert_eq!(sci(-6.2e-8, 0), "−6e-8");
            assert_eq!(sci(1.27e-13, 1), "1.3e-13");
            assert_eq!(sci(-0.0, 0), "0");
        }

        #[test]
        fn write_if_requested_writes_only_when_asked() {
            let dir = std::env::temp_dir().join(format!(
                "jbearing-generated-requested-{}",
                std::process::id()
            ));
            std::fs::create_dir_all(&dir).unwrap();
            let page = dir.join("page.md");
            std::fs::write(&page, PAGE).unwrap();
            assert!(!write_if_requested_to(false, &page, "cmd a", "| t |").unwrap());
            assert_eq!(std::fs::read_to_string(&page).unwrap(), PAGE);
            assert!(write_if_requested_to(true, &page, "cmd a", "| t |").unwrap());
            let out = std::fs::read_to_string(&page).unwrap();
            let block = out
                .split("<!-- BEGIN generated: cmd a -->\n")
                .nth(1)
                .and_then(|r| r.split(END_MARKER).next())
                .unwrap();
            // The measured line, a blank line, the table; the other block untouched.
            let mut lines = block.lines();
            let first = lines.next().unwrap();
            assert!(first.starts_with("Measured 20"), "{first}");
            assert!(first.ends_with("build) by `cmd a`."), "{first}");
            assert_eq!(lines.collect::<Vec<_>>(), ["", "| t |"]);
            assert!(out.contains("old b\n"));
            // Asked for a block the page lacks: an error, not a silent skip.
            assert!(write_if_requested_to(true, &page, "cmd z", "x").is_err());
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
