//! Parameter sweeps: a case file with a `[sweep]` table stands for many cases, one per point of
//! the sweep, each an ordinary case whose swept keys are replaced.
//!
//! ```toml
//! [sweep]
//! combine = "factorial"            # every combination (default), or "zip": the i-th values together
//! [sweep.values]
//! "bearing.radial_clearance_m" = [2.0e-5, 2.54e-5, 3.0e-5]                  # a list
//! "lubricant.heat_balance.supply_temperature_c" = { start = 40.0, stop = 80.0, count = 5 }
//! "operation.crank_speed_rpm" = { start = 900.0, stop = 3600.0, count = 3, spacing = "log" }
//! ```
//!
//! Keys are dotted paths into the case file (`grooves.0.center_angle_deg` for an entry of an
//! array of tables); every value must be a number (integers stay integers: a range whose ends
//! are integers and whose points all are, such as a grid size, gives integers). The expansion is
//! deterministic: keys in the order of the file's `[sweep.values]` (sorted by name, as TOML
//! tables are), values in the order given, the last key varying fastest; each point is a case
//! named `NAME__key1_value1__key2_value2` (key = the path's last part, value in its shortest
//! exact form), so a point keeps its name — and its output files and its shard — whatever else
//! the sweep or the batch holds.
//!
//! ```text
//!   case.toml ──toml──► table ─┬─ remove [sweep] ─► base table
//!                              └─ [sweep] ──► points (factorial / zip)
//!   each point: base table + values at their paths + name ──► TOML text ──► Case::from_text
//! ```

use std::path::{Path, PathBuf};

use crate::case::{Case, CaseError};

/// Name of the sweep table in a case file.
pub const SWEEP_TABLE: &str = "sweep";

/// One case of a batch: a case file, or one point of a case file's sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct CaseJob {
    /// The case file it comes from (relative paths in it resolve from there).
    pub path: PathBuf,
    /// The case's name (the point's, for a sweep).
    pub name: String,
    /// The expanded case text of a sweep point; `None`: the file as it is.
    pub text: Option<String>,
    /// The swept keys and their values at this point (empty for a plain case).
    pub parameters: Vec<SweptValue>,
}

/// A swept key's value at a point.
#[derive(Debug, Clone, PartialEq)]
pub struct SweptValue {
    /// The dotted key path, e.g. `bearing.radial_clearance_m`.
    pub key: String,
    /// Its value.
    pub value: f64,
}

impl SweptValue {
    /// The name the key goes by in merged datasets and sub-case names: its last path part.
    pub fn short_name(&self) -> &str {
        self.key.rsplit('.').next().unwrap_or(&self.key)
    }
}

impl CaseJob {
    /// The case, parsed (from the file, or from the point's expanded text).
    pub fn case(&self) -> Result<Case, CaseError> {
        match &self.text {
            None => Case::from_file(&self.path),
            Some(text) => Case::from_text(text, &self.path).map_err(|e| {
                // Errors of a point name the point (its keys and values are what differ from
                // the file the user wrote) at the line of the file's sweep table.
                let original = std::fs::read_to_string(&self.path).unwrap_or_default();
                CaseError::Key {
                    file: self.path.clone(),
                    line: line_of(&original, &format!("[{SWEEP_TABLE}")),
                    key: format!("{SWEEP_TABLE} point '{}'", self.name),
                    message: e.to_string(),
                }
            }),
        }
    }
}

/// 1-based line of the first line of `text` that contains `needle` (1 if none).
fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .map_or(1, |i| i + 1)
}

/// A sweep error at `key` (a dotted path under `[sweep]`), with the line of the key's last part
/// in the file (or of the sweep table).
fn invalid(path: &Path, key: &str, message: impl Into<String>) -> CaseError {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    let last = key.strip_prefix("sweep.values.").unwrap_or(key);
    let last = last.rsplit('.').next().unwrap_or(last);
    let line = text
        .lines()
        .position(|l| l.contains(last) && !l.trim_start().starts_with('#'))
        .map_or_else(|| line_of(&text, &format!("[{SWEEP_TABLE}")), |i| i + 1);
    CaseError::Key {
        file: path.to_path_buf(),
        line,
        key: key.into(),
        message: message.into(),
    }
}

/// The jobs of `path`: one for a plain case file, one per point for a file with `[sweep]`.
/// A file that cannot be read or parsed as TOML gives one job (its error comes when it runs).
pub fn expand_file(path: &Path) -> Result<Vec<CaseJob>, CaseError> {
    let plain = |name: String| CaseJob {
        path: path.to_path_buf(),
        name,
        text: None,
        parameters: Vec::new(),
    };
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let Ok(text) = std::fs::read_to_string(path) else {
        return Ok(vec![plain(stem)]);
    };
    let Ok(mut table) = text.parse::<toml::Table>() else {
        return Ok(vec![plain(stem)]);
    };
    let name = table
        .get("name")
        .and_then(|v| v.as_str())
        .map_or(stem, str::to_owned);
    let Some(sweep) = table.remove(SWEEP_TABLE) else {
        return Ok(vec![plain(name)]);
    };
    let sweep = sweep
        .as_table()
        .ok_or_else(|| invalid(path, SWEEP_TABLE, "must be a table"))?
        .clone();
    let points = sweep_points(path, &sweep)?;
    points
        .into_iter()
        .map(|values| {
            let point_name = std::iter::once(name.clone())
                .chain(
                    values
                        .iter()
                        .map(|(k, v)| format!("{}_{}", short(k), format_value(v))),
                )
                .collect::<Vec<_>>()
                .join("__");
            let mut t = table.clone();
            for (key, value) in &values {
                set_path(&mut t, key, value.clone())
                    .map_err(|m| invalid(path, &format!("{SWEEP_TABLE}.values.{key}"), m))?;
            }
            t.insert("name".into(), toml::Value::String(point_name.clone()));
            let text = toml::to_string(&t).map_err(|e| {
                invalid(
                    path,
                    SWEEP_TABLE,
                    format!("the point does not serialise: {e}"),
                )
            })?;
            Ok(CaseJob {
                path: path.to_path_buf(),
                name: point_name,
                text: Some(text),
                parameters: values
                    .iter()
                    .map(|(k, v)| SweptValue {
                        key: k.clone(),
                        value: v
                            .as_float()
                            .or(v.as_integer().map(|i| i as f64))
                            .unwrap_or(f64::NAN),
                    })
                    .collect(),
            })
        })
        .collect()
}

/// The jobs of every file, in order.
pub fn expand_all(paths: &[PathBuf]) -> Result<Vec<CaseJob>, CaseError> {
    let mut jobs = Vec::new();
    for p in paths {
        jobs.extend(expand_file(p)?);
    }
    Ok(jobs)
}

fn short(key: &str) -> &str {
    key.rsplit('.').next().unwrap_or(key)
}

/// A value in its shortest exact form for names: integers as integers, other numbers as
/// Rust prints them shortest-round-trip (`2.54e-5`, `60.5`).
fn format_value(v: &toml::Value) -> String {
    match v {
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Float(x) => {
            let plain = format!("{x}");
            let sci = format!("{x:e}");
            if plain.len() <= sci.len() { plain } else { sci }
        }
        other => other.to_string(),
    }
}

/// The points of a sweep: for each, the (key, value) pairs in key order.
fn sweep_points(
    path: &Path,
    sweep: &toml::Table,
) -> Result<Vec<Vec<(String, toml::Value)>>, CaseError> {
    let (combine, axes) = sweep_axes(path, sweep)?;
    combine_axes(path, combine, &axes)
}

/// Each swept key with its values, in key order.
type Axes = Vec<(String, Vec<toml::Value>)>;

/// The sweep table checked: how to combine (`factorial` or `zip`) and each swept key's values.
fn sweep_axes<'a>(path: &Path, sweep: &'a toml::Table) -> Result<(&'a str, Axes), CaseError> {
    for key in sweep.keys() {
        if key != "combine" && key != "values" {
            return Err(invalid(
                path,
                &format!("{SWEEP_TABLE}.{key}"),
                "unknown key (the sweep table takes `combine` and `values`)",
            ));
        }
    }
    let combine = match sweep.get("combine") {
        None => "factorial",
        Some(toml::Value::String(s)) if s == "factorial" || s == "zip" => s.as_str(),
        Some(other) => {
            return Err(invalid(
                path,
                &format!("{SWEEP_TABLE}.combine"),
                format!("must be \"factorial\" or \"zip\", got {other}"),
            ));
        }
    };
    let values = sweep
        .get("values")
        .and_then(|v| v.as_table())
        .ok_or_else(|| {
            invalid(
                path,
                &format!("{SWEEP_TABLE}.values"),
                "missing: a table of swept keys, each a list or a range",
            )
        })?;
    if values.is_empty() {
        return Err(invalid(
            path,
            &format!("{SWEEP_TABLE}.values"),
            "sweeps no key",
        ));
    }
    let mut axes: Axes = Vec::new();
    for (key, spec) in values {
        let here = format!("{SWEEP_TABLE}.values.{key}");
        if key == "name" || key.starts_with(&format!("{SWEEP_TABLE}.")) {
            return Err(invalid(path, &here, "cannot be swept"));
        }
        let list = axis_values(spec).map_err(|m| invalid(path, &here, m))?;
        axes.push((key.clone(), list));
    }
    Ok((combine, axes))
}

/// The points of `axes` combined: the i-th values of each (`zip`, all of one length) or every
/// combination (`factorial`, the last key varying fastest).
fn combine_axes(
    path: &Path,
    combine: &str,
    axes: &[(String, Vec<toml::Value>)],
) -> Result<Vec<Vec<(String, toml::Value)>>, CaseError> {
    match combine {
        "zip" => {
            let n = axes[0].1.len();
            if let Some((key, v)) = axes.iter().find(|(_, v)| v.len() != n) {
                return Err(invalid(
                    path,
                    &format!("{SWEEP_TABLE}.values.{key}"),
                    format!(
                        "has {} values, but combine = \"zip\" needs as many as `{}` ({n})",
                        v.len(),
                        axes[0].0
                    ),
                ));
            }
            Ok((0..n)
                .map(|i| {
                    axes.iter()
                        .map(|(k, v)| (k.clone(), v[i].clone()))
                        .collect()
                })
                .collect())
        }
        _ => {
            let mut points: Vec<Vec<(String, toml::Value)>> = vec![Vec::new()];
            for (key, list) in axes {
                points = points
                    .into_iter()
                    .flat_map(|p| {
                        list.iter().map(move |v| {
                            let mut q = p.clone();
                            q.push((key.clone(), v.clone()));
                            q
                        })
                    })
                    .collect();
            }
            Ok(points)
        }
    }
}

/// The values of one swept key: a list of numbers, or a range table
/// `{ start, stop, count, spacing = "linear" | "log" }` (both ends included).
fn axis_values(spec: &toml::Value) -> Result<Vec<toml::Value>, String> {
    let number = |v: &toml::Value| v.as_float().or(v.as_integer().map(|i| i as f64));
    match spec {
        toml::Value::Array(list) => {
            if list.is_empty() {
                return Err("an empty list".into());
            }
            for v in list {
                match number(v) {
                    Some(x) if x.is_finite() => {}
                    _ => return Err(format!("{v} is not a finite number")),
                }
            }
            Ok(list.clone())
        }
        toml::Value::Table(t) => {
            for key in t.keys() {
                if !["start", "stop", "count", "spacing"].contains(&key.as_str()) {
                    return Err(format!(
                        "unknown range key `{key}` (start, stop, count, spacing)"
                    ));
                }
            }
            let get = |k: &str| t.get(k).and_then(number);
            let (Some(start), Some(stop)) = (get("start"), get("stop")) else {
                return Err("a range needs start and stop".into());
            };
            let count = t
                .get("count")
                .and_then(|v| v.as_integer())
                .ok_or("a range needs an integer count")?;
            if !(1..=100_000).contains(&count) || !start.is_finite() || !stop.is_finite() {
                return Err(format!(
                    "count must lie in 1 … 100000 and the ends be finite (start {start}, stop \
                     {stop}, count {count})"
                ));
            }
            let log = match t.get("spacing").and_then(|v| v.as_str()) {
                None | Some("linear") => false,
                Some("log") => true,
                Some(other) => return Err(format!("spacing must be linear or log, got {other}")),
            };
            if log && !(start > 0.0 && stop > 0.0) {
                return Err("a log range needs positive ends".into());
            }
            let n = count as usize;
            let at = |i: usize| {
                if n == 1 {
                    return start;
                }
                let s = i as f64 / (n - 1) as f64;
                if i == n - 1 {
                    stop
                } else if log {
                    (start.ln() + s * (stop.ln() - start.ln())).exp()
                } else {
                    start + s * (stop - start)
                }
            };
            let values: Vec<f64> = (0..n).map(at).collect();
            let integers = t.get("start").is_some_and(|v| v.is_integer())
                && t.get("stop").is_some_and(|v| v.is_integer())
                && values.iter().all(|v| v.fract() == 0.0);
            Ok(values
                .into_iter()
                .map(|v| {
                    if integers {
                        toml::Value::Integer(v as i64)
                    } else {
                        toml::Value::Float(v)
                    }
                })
                .collect())
        }
        other => Err(format!(
            "must be a list of numbers or a range table, got {other}"
        )),
    }
}

/// Set `value` at the dotted `path` of `table`, making tables on the way; a numeric part
/// indexes an array (of tables).
fn set_path(table: &mut toml::Table, path: &str, value: toml::Value) -> Result<(), String> {
    let parts: Vec<&str> = path.split('.').collect();
    let mut here = table;
    for (i, part) in parts.iter().enumerate() {
        let last = i + 1 == parts.len();
        if last {
            here.insert((*part).to_string(), value);
            return Ok(());
        }
        let next = parts[i + 1];
        let entry = here
            .entry((*part).to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        here = match entry {
            toml::Value::Table(t) => t,
            toml::Value::Array(a) => {
                let index: usize = next
                    .parse()
                    .map_err(|_| format!("`{part}` is a list: give an index, e.g. {part}.0"))?;
                let len = a.len();
                let t = a
                    .get_mut(index)
                    .ok_or(format!("`{part}` has {len} entries, no {index}"))?;
                // Skip the index part.
                let rest = parts[i + 2..].join(".");
                return match t {
                    toml::Value::Table(t) if !rest.is_empty() => set_path(t, &rest, value),
                    _ => Err(format!("`{part}.{index}` is not a table of keys")),
                };
            }
            _ => return Err(format!("`{part}` is a value, not a table")),
        };
    }
    Ok(())
}

/// The shard (0 … count − 1) a case named `name` belongs to: FNV-1a (64-bit) of the name,
/// modulo the count. The same name always lands in the same shard, whatever the order or the
/// other contents of the batch.
pub fn shard_of(name: &str, count: usize) -> usize {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in name.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    (h % count.max(1) as u64) as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write_case(dir: &Path, sweep: &str) -> PathBuf {
        let text = crate::case::test_case_text(
            "swept",
            "crank_angle_deg = [0.0, 180.0]\nx_n = [-1000.0, -500.0]\ny_n = [0.0, 0.0]",
            sweep,
        );
        let p = dir.join("swept.toml");
        std::fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn factorial_and_zip_expand_in_order_with_stable_names() {
        let dir = tempfile::tempdir().unwrap();
        let p = write_case(
            dir.path(),
            "\n[sweep]\n[sweep.values]\n\"bearing.radial_clearance_m\" = [4e-5, 5e-5]\n\
             \"grid.n_theta\" = { start = 60, stop = 120, count = 3 }\n",
        );
        let jobs = expand_file(&p).unwrap();
        let names: Vec<&str> = jobs.iter().map(|j| j.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "swept__radial_clearance_m_4e-5__n_theta_60",
                "swept__radial_clearance_m_4e-5__n_theta_90",
                "swept__radial_clearance_m_4e-5__n_theta_120",
                "swept__radial_clearance_m_5e-5__n_theta_60",
                "swept__radial_clearance_m_5e-5__n_theta_90",
                "swept__radial_clearance_m_5e-5__n_theta_120",
            ]
        );
        let case = jobs[4].case().unwrap();
        assert_eq!((case.radial_clearance, case.n_theta), (5e-5, 90));
        assert_eq!(case.name, jobs[4].name);

        let z = write_case(
            dir.path(),
            "\n[sweep]\ncombine = \"zip\"\n[sweep.values]\n\"bearing.radial_clearance_m\" = [4e-5, 5e-5]\n\
             \"lubricant.viscosity_pa_s\" = { start = 0.01, stop = 0.1, count = 2, spacing = \"log\" }\n",
        );
        let jobs = expand_file(&z).unwrap();
        assert_eq!(jobs.len(), 2);
        let c = jobs[1].case().unwrap();
        assert_eq!((c.radial_clearance, c.viscosity), (5e-5, 0.1));
        assert_eq!(jobs[1].parameters[1].short_name(), "viscosity_pa_s");
    }

    #[test]
    fn bad_sweeps_name_their_key() {
        let dir = tempfile::tempdir().unwrap();
        for (sweep, key) in [
            (
                "\n[sweep]\n[sweep.values]\n\"bearing.radial_clearance_m\" = []\n",
                "sweep.values.bearing.radial_clearance_m",
            ),
            (
                "\n[sweep]\ncombine = \"all\"\n[sweep.values]\n\"grid.n_z\" = [9]\n",
                "sweep.combine",
            ),
            (
                "\n[sweep]\ncombine = \"zip\"\n[sweep.values]\n\"grid.n_z\" = [9, 11]\n\"grid.n_theta\" = [36]\n",
                "sweep.values.grid.n_z",
            ),
            (
                "\n[sweep]\n[sweep.values]\n\"grid.n_z\" = { start = 9, stop = 11 }\n",
                "sweep.values.grid.n_z",
            ),
            ("\n[sweep]\nvalue = 1\n", "sweep.value"),
        ] {
            let p = write_case(dir.path(), sweep);
            let err = expand_file(&p).unwrap_err().to_string();
            assert!(err.contains(key), "{key}: {err}");
        }
        // A typo in a swept key is the sub-case's unknown key, named with the point.
        let p = write_case(
            dir.path(),
            "\n[sweep]\n[sweep.values]\n\"bearing.radial_clearanse_m\" = [4e-5]\n",
        );
        let err = expand_file(&p).unwrap()[0].case().unwrap_err().to_string();
        assert!(err.contains("radial_clearanse_m"), "{err}");
        assert!(err.contains("sweep point"), "{err}");
    }

    #[test]
    fn shards_are_stable_and_spread() {
        let names: Vec<String> = (0..400).map(|i| format!("case__x_{i}")).collect();
        let mut counts = [0usize; 4];
        for n in &names {
            let s = shard_of(n, 4);
            assert_eq!(s, shard_of(n, 4));
            counts[s] += 1;
        }
        // 400 names over 4 shards: each within ±30 % of 100 (binomial sd ≈ 8.7).
        assert!(
            counts.iter().all(|&c| (70..=130).contains(&c)),
            "{counts:?}"
        );
        assert_eq!(shard_of("anything", 1), 0);
    }
}
