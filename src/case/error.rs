//! Errors of case files, with the place named: file, key and line.
//!
//! The TOML text is parsed twice: once into the typed schema (serde, `deny_unknown_fields`) and
//! once into toml's spanned document tree ([`Locator`]), which maps a key path such as
//! `bearing.radius_m` or `grooves[1].axial_width_m` to its line, and an error's byte offset back
//! to the key it lies in. Every message has the form
//!
//! ```text
//!   FILE:LINE: KEY: what is wrong
//!   CSV:LINE: what is wrong (table given by KEY at FILE:LINE)
//! ```

use std::ops::Range;
use std::path::PathBuf;

use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// What is wrong with a case (or compressor) file.
#[derive(Debug, thiserror::Error)]
pub enum CaseError {
    /// The file could not be read.
    #[error("{}: cannot read the file: {source}", file.display())]
    Read {
        /// The file.
        file: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// Not valid TOML.
    #[error("{}:{line}:{column}: {key}: TOML syntax error: {message}", file.display())]
    Syntax {
        /// The file.
        file: PathBuf,
        /// The key on the offending line (the text before `=`), or the line's text.
        key: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// A key is unknown, missing, of the wrong type or has a bad value.
    #[error("{}:{line}: {key}: {message}", file.display())]
    Key {
        /// The file.
        file: PathBuf,
        /// 1-based line of the key (or of its table, for a missing key).
        line: usize,
        /// Dotted key path, e.g. `bearing.radius_m`.
        key: String,
        /// What is wrong.
        message: String,
    },
    /// A CSV table the case refers to is missing or has a bad row.
    #[error("{}:{csv_line}: {message} (table given by {key} at {}:{line})", csv.display(), file.display())]
    Csv {
        /// The CSV file.
        csv: PathBuf,
        /// 1-based line in the CSV file (0 if the file could not be opened).
        csv_line: usize,
        /// What is wrong.
        message: String,
        /// The case file.
        file: PathBuf,
        /// The key that names the table.
        key: String,
        /// Line of that key in the case file.
        line: usize,
    },
}

/// Something in a valid case that a user should look at before trusting the results: a value
/// far outside what journal bearings have (1 nm clearance, a 100 MPa specific load), or a case
/// whose estimated cost is above the soft budget. Printed by `check`, `run` and `batch`
/// (`warning: FILE:LINE: KEY: message`) and written into the result file.
#[derive(Debug, Clone, PartialEq)]
pub struct CaseWarning {
    /// The case file.
    pub file: PathBuf,
    /// 1-based line of the key.
    pub line: usize,
    /// Dotted key path.
    pub key: String,
    /// What kind of warning.
    pub kind: WarningKind,
    /// What is unusual and why it matters.
    pub message: String,
}

/// The kinds of [`CaseWarning`]; `as_str` is what the result file stores.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WarningKind {
    /// A value far outside the range of journal bearings (probably a unit or typing error).
    Implausible,
    /// The case's estimated memory or time is above the soft budget.
    Budget,
}

impl WarningKind {
    /// `"implausible"` or `"budget"`.
    pub fn as_str(self) -> &'static str {
        match self {
            WarningKind::Implausible => "implausible",
            WarningKind::Budget => "budget",
        }
    }
}

impl std::fmt::Display for CaseWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}:{}: {}: {}",
            self.file.display(),
            self.line,
            self.key,
            self.message
        )
    }
}

/// 1-based line and column of a byte offset.
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// Key paths ↔ lines of one TOML document.
pub struct Locator<'a> {
    text: &'a str,
    root: Option<Spanned<DeTable<'a>>>,
}

impl<'a> Locator<'a> {
    /// Parse `text` for spans (a syntax error leaves the locator empty: lines fall back to 1).
    pub fn new(text: &'a str) -> Self {
        Self {
            text,
            root: DeTable::parse(text).ok(),
        }
    }

    /// Line of the key at `path` (`a.b`, `a[2].c`); for a path that does not exist, the line of
    /// its deepest existing ancestor (the table a missing key belongs in), else 1.
    pub fn line_of(&self, path: &str) -> usize {
        let Some(root) = &self.root else { return 1 };
        let mut best: Option<usize> = None;
        let mut table: &DeTable<'_> = root.get_ref();
        let mut current: Option<&Spanned<DeValue<'_>>>;
        for seg in path.split('.') {
            let (name, index) = match seg.find('[') {
                Some(i) => (
                    &seg[..i],
                    seg[i + 1..].trim_end_matches(']').parse::<usize>().ok(),
                ),
                None => (seg, None),
            };
            let Some((k, v)) = table.get_key_value(name) else {
                break;
            };
            best = Some(k.span().start);
            current = Some(v);
            if let (Some(i), DeValue::Array(a)) = (index, v.get_ref()) {
                let item: Option<&Spanned<DeValue<'_>>> = a.get(i);
                match item {
                    Some(item) => {
                        best = Some(item.span().start);
                        current = Some(item);
                    }
                    None => break,
                }
            }
            match current.map(|c| c.get_ref()) {
                Some(DeValue::Table(t)) => table = t,
                _ => break,
            }
        }
        best.map_or(1, |o| line_column(self.text, o).0)
    }

    /// The dotted path of the innermost key whose key or value contains the byte range `span`.
    pub fn key_at(&self, span: &Range<usize>) -> Option<String> {
        let root = self.root.as_ref()?;
        let mut entries = Vec::new();
        flatten(root.get_ref(), "", &mut entries);
        let inside = |r: &Range<usize>| r.start <= span.start && span.end <= r.end;
        entries
            .into_iter()
            .filter(|(_, k, v)| inside(k) || inside(v))
            .min_by_key(|(_, k, v)| if inside(k) { k.len() } else { v.len() })
            .map(|(p, _, _)| p)
    }
}

/// Every key of `table` (recursively, arrays of tables indexed) with its key and value spans.
fn flatten(table: &DeTable<'_>, prefix: &str, out: &mut Vec<(String, Range<usize>, Range<usize>)>) {
    for (k, v) in table.iter() {
        let path = if prefix.is_empty() {
            k.get_ref().to_string()
        } else {
            format!("{prefix}.{}", k.get_ref())
        };
        out.push((path.clone(), k.span(), v.span()));
        match v.get_ref() {
            DeValue::Table(t) => flatten(t, &path, out),
            DeValue::Array(a) => {
                for (i, item) in a.iter().enumerate() {
                    let item: &Spanned<DeValue<'_>> = item;
                    let ip = format!("{path}[{i}]");
                    out.push((ip.clone(), item.span(), item.span()));
                    if let DeValue::Table(t) = item.get_ref() {
                        flatten(t, &ip, out);
                    }
                }
            }
            _ => {}
        }
    }
}
