//! `jbearing merge DIR… --out FILE.nc`: the cases of a (sharded) batch in one netCDF-4 dataset
//! along a `case` dimension, with the swept parameters as coordinates.
//!
//! ```text
//!   DIR/shard_I_of_N.json (every case of the batch, its shard, this shard's outcome)
//!   DIR/CASE.h5           (each solved case)
//!        ──► expected cases = the manifests' list (expansion order), status per case:
//!            ok | failed: <why> | missing: <no manifest for its shard / no CASE.h5>
//!            | ok (mechanism case: not merged) (listed, its numbers left NaN)
//!        ──► FILE.nc:
//!   case(case)                          case names
//!   <swept key>(case)                   e.g. radial_clearance_m, supply_temperature_c
//!   status(case)                        "ok", "failed: …", "missing: …"
//!   solution_method(solution_method)    "rigorous", "mobility"
//!   <summary row>(case, solution_method) min_film_thickness_min, effective_temperature, …
//!   crank_angle(crank_angle)            the first solved case's crank grid
//!   <method>_<series>(case, crank_angle) rigorous_min_film_thickness, mobility_power_loss, …
//! ```
//!
//! Every value is NaN where a case lacks it (failed, missing, a method not asked for, a crank
//! grid of another length). The file holds no time stamps or wall times, so merging the same
//! results gives the same numbers whatever the sharding (tested bit for bit). In xarray:
//! `xr.open_dataset("sweep.nc").set_xindex("radial_clearance_m").sel(radial_clearance_m=2.54e-5)`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use hdf5_metno as h5;
use hdf5_metno::types::VarLenUnicode;
use ndarray::Array2;

use crate::batch::{Manifest, ManifestCase};
use crate::output::hdf5::FileWriter;
use crate::output::{Method, OutputError, write_atomically};

/// Why a merge could not be made.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// No manifest in any directory.
    #[error(
        "no shard manifest (shard_I_of_N.json) in {dirs}: merge reads the directories that \
         `jbearing batch` wrote"
    )]
    NoManifest {
        /// The directories given.
        dirs: String,
    },
    /// A manifest cannot be read.
    #[error("{}: {message}", path.display())]
    Manifest {
        /// The manifest.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// Manifests of different shardings (N) or of different batches.
    #[error("{}: {message}", path.display())]
    Inconsistent {
        /// The manifest that disagrees.
        path: PathBuf,
        /// How.
        message: String,
    },
    /// A result file cannot be read.
    #[error("{}: cannot read it: {source}", path.display())]
    Read {
        /// The CASE.h5.
        path: PathBuf,
        /// The HDF5 error.
        #[source]
        source: h5::Error,
    },
    /// Writing the merged file failed.
    #[error(transparent)]
    Write(#[from] OutputError),
}

/// What a merge found: per case its status, in the batch's order.
#[derive(Debug, Clone, PartialEq)]
pub struct MergeInfo {
    /// (case, status) for every case of the batch: "ok", "failed: …" or "missing: …".
    pub cases: Vec<(String, String)>,
}

impl MergeInfo {
    /// The cases that are not "ok".
    pub fn incomplete(&self) -> Vec<&(String, String)> {
        self.cases
            .iter()
            .filter(|(_, s)| s != "ok" && s != MECHANISM_NOT_MERGED)
            .collect()
    }
}

/// A series of one method read back: (units, long name, crank angles, values).
type SeriesData = (String, String, Vec<f64>, Vec<f64>);

/// One case's numbers read from its CASE.h5.
#[derive(Debug, Default)]
struct CaseNumbers {
    /// Summary rows: name → (units, long name, [rigorous, mobility]).
    summary: BTreeMap<String, (String, String, [f64; 2])>,
    /// Series: (method, name) → its data.
    series: BTreeMap<(String, String), SeriesData>,
}

fn read_case(path: &Path) -> Result<CaseNumbers, MergeError> {
    let err = |source| MergeError::Read {
        path: path.to_path_buf(),
        source,
    };
    let file = h5::File::open(path).map_err(err)?;
    let text_attr = |ds: &h5::Dataset, name: &str| -> String {
        ds.attr(name)
            .and_then(|a| a.read_scalar::<VarLenUnicode>())
            .map(|v| v.as_str().to_owned())
            .unwrap_or_default()
    };
    let mut out = CaseNumbers::default();
    if let Ok(g) = file.group("summary") {
        let labels: Vec<VarLenUnicode> = g
            .dataset("solution_method")
            .and_then(|d| d.read_raw())
            .map_err(err)?;
        for name in g.member_names().map_err(err)? {
            if name == "solution_method" {
                continue;
            }
            let ds = g.dataset(&name).map_err(err)?;
            let values: Vec<f64> = ds.read_raw().map_err(err)?;
            let mut both = [f64::NAN; 2];
            for (label, v) in labels.iter().zip(values) {
                if let Some(k) = Method::ALL
                    .iter()
                    .position(|m| m.as_str() == label.as_str())
                {
                    both[k] = v;
                }
            }
            out.summary.insert(
                name,
                (text_attr(&ds, "units"), text_attr(&ds, "long_name"), both),
            );
        }
    }
    for m in Method::ALL {
        let Ok(g) = file.group(m.as_str()) else {
            continue;
        };
        let crank: Vec<f64> = g
            .dataset("crank_angle")
            .and_then(|d| d.read_raw())
            .map_err(err)?;
        for name in g.member_names().map_err(err)? {
            let Ok(ds) = g.dataset(&name) else {
                continue; // the fields/ group
            };
            if name == "crank_angle" || name == "time" || ds.ndim() != 1 {
                continue;
            }
            let values: Vec<f64> = ds.read_raw().map_err(err)?;
            out.series.insert(
                (m.as_str().to_owned(), name),
                (
                    text_attr(&ds, "units"),
                    text_attr(&ds, "long_name"),
                    crank.clone(),
                    values,
                ),
            );
        }
    }
    Ok(out)
}

/// The manifests in `dirs` (`shard_*_of_*.json`), with their paths.
fn read_manifests(dirs: &[PathBuf]) -> Result<Vec<(PathBuf, Manifest)>, MergeError> {
    let mut found = Vec::new();
    for dir in dirs {
        let Ok(entries) = std::fs::read_dir(dir) else {
            continue;
        };
        let mut paths: Vec<PathBuf> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| {
                p.file_name().and_then(|n| n.to_str()).is_some_and(|n| {
                    n.starts_with("shard_") && n.ends_with(".json") && n.contains("_of_")
                })
            })
            .collect();
        paths.sort();
        for p in paths {
            let text = std::fs::read_to_string(&p).map_err(|e| MergeError::Manifest {
                path: p.clone(),
                message: e.to_string(),
            })?;
            let m: Manifest = serde_json::from_str(&text).map_err(|e| MergeError::Manifest {
                path: p.clone(),
                message: format!("not a shard manifest: {e}"),
            })?;
            found.push((p, m));
        }
    }
    Ok(found)
}

/// Status of a mechanism case whose `CASE.h5` is there (its numbers are not merged).
pub const MECHANISM_NOT_MERGED: &str = "ok (mechanism case: not merged)";

/// Merge the batch results in `dirs` into `out` (written atomically); the status of every case.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<MergeInfo, MergeError> {
    let manifests = read_manifests(dirs)?;
    let Some((first_path, first)) = manifests.first() else {
        return Err(MergeError::NoManifest {
            dirs: dirs
                .iter()
                .map(|d| d.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
        });
    };
    let shards = first.shards;
    let names: Vec<&str> = first.cases.iter().map(|c| c.name.as_str()).collect();
    // Which shard's manifest says what about each of its cases.
    let mut own: BTreeMap<usize, &Manifest> = BTreeMap::new();
    for (path, m) in &manifests {
        let same_cases =
            m.cases.len() == names.len() && m.cases.iter().zip(&names).all(|(c, n)| c.name == *n);
        if m.shards != shards || !same_cases {
            return Err(MergeError::Inconsistent {
                path: path.clone(),
                message: format!(
                    "belongs to another batch than {} ({} shards and {} cases there, {} and {} \
                     here): merge the directories of one batch",
                    first_path.display(),
                    shards,
                    names.len(),
                    m.shards,
                    m.cases.len()
                ),
            });
        }
        // A re-run of a shard writes the same manifest name: the latest read wins (sorted).
        own.insert(m.shard, m);
    }
    let mut statuses = Vec::new();
    let mut numbers: Vec<Option<CaseNumbers>> = Vec::new();
    for case in &first.cases {
        let (status, nums) = case_status(case, &own, shards, dirs)?;
        statuses.push(status);
        numbers.push(nums);
    }
    write_merged(out, &first.cases, &statuses, &numbers)?;
    Ok(MergeInfo {
        cases: first
            .cases
            .iter()
            .map(|c| c.name.clone())
            .zip(statuses)
            .collect(),
    })
}

/// What the merged file says of one case: ok (with its numbers), failed or missing, and why.
fn case_status(
    case: &ManifestCase,
    own: &BTreeMap<usize, &Manifest>,
    shards: usize,
    dirs: &[PathBuf],
) -> Result<(String, Option<CaseNumbers>), MergeError> {
    let entry: Option<&ManifestCase> = own
        .get(&case.shard)
        .and_then(|m| m.cases.iter().find(|c| c.name == case.name));
    Ok(match entry {
        None => (
            format!(
                "missing: shard {} of {} has no manifest (not run, or its directory not given)",
                case.shard, shards
            ),
            None,
        ),
        Some(c) if c.status == "failed" => (format!("failed: {}", c.message), None),
        // Mechanism cases have no bearing-case groups to merge: listed, not merged.
        Some(c) if c.kind == crate::batch::KIND_MECHANISM => match find_h5(dirs, &case.name) {
            Some(_) => (MECHANISM_NOT_MERGED.to_string(), None),
            None => (
                format!("missing: no {}.h5 in the directories given", case.name),
                None,
            ),
        },
        Some(_) => match find_h5(dirs, &case.name) {
            Some(p) => ("ok".to_string(), Some(read_case(&p)?)),
            None => (
                format!("missing: no {}.h5 in the directories given", case.name),
                None,
            ),
        },
    })
}

/// The first `NAME.h5` among `dirs`.
fn find_h5(dirs: &[PathBuf], name: &str) -> Option<PathBuf> {
    dirs.iter()
        .map(|d| d.join(format!("{name}.h5")))
        .find(|p| p.is_file())
}

/// The merged file: every case's status, swept keys, summary rows and series along `case`
/// (NaN where a case has no value).
fn write_merged(
    out: &Path,
    cases: &[ManifestCase],
    statuses: &[String],
    numbers: &[Option<CaseNumbers>],
) -> Result<(), MergeError> {
    // The union of summary rows and series over the cases, with the first units seen.
    let mut rows: BTreeMap<&str, (&str, &str)> = BTreeMap::new();
    let mut series: BTreeMap<(&str, &str), (&str, &str)> = BTreeMap::new();
    let mut crank: Option<&Vec<f64>> = None;
    for c in numbers.iter().flatten() {
        for (k, (u, l, _)) in &c.summary {
            rows.entry(k).or_insert((u, l));
        }
        for ((m, s), (u, l, angles, _)) in &c.series {
            series.entry((m, s)).or_insert((u, l));
            crank.get_or_insert(angles);
        }
    }
    let crank: Vec<f64> = crank.cloned().unwrap_or_default();
    // Swept keys: the parameters of the first case, by full key (their order in the sweep).
    let keys: Vec<String> = cases
        .first()
        .map(|c| c.parameters.iter().map(|(k, _)| k.clone()).collect())
        .unwrap_or_default();
    write_atomically(out, |tmp| {
        let file = h5::File::create(tmp).map_err(|source| OutputError::Hdf5 {
            path: out.to_path_buf(),
            context: "creating the file".into(),
            source,
        })?;
        let mut w = FileWriter::new(out);
        w.str_attr(&file, "Conventions", crate::output::layout::CONVENTIONS)?;
        w.str_attr(
            &file,
            "title",
            "jbearing batch results merged along the case dimension",
        )?;
        w.str_attr(
            &file,
            "source",
            &format!("jbearing {} merge", env!("CARGO_PKG_VERSION")),
        )?;
        let root = file.as_group().map_err(w.err("root group"))?;
        let (case, coordinates) = write_cases(&mut w, &root, cases, statuses, &keys)?;
        let labels: Vec<String> = Method::ALL.iter().map(|m| m.as_str().to_owned()).collect();
        let sm = crate::output::layout::SOLUTION_METHOD;
        let method = w.string_coordinate(&root, sm.name, &labels, sm.long_name)?;
        write_summary_rows(
            &mut w,
            &root,
            &rows,
            numbers,
            [&case, &method],
            &coordinates,
        )?;
        if !crank.is_empty() {
            write_series(&mut w, &root, &series, numbers, &crank, &case, &coordinates)?;
        }
        file.close().map_err(w.err("closing the file"))
    })?;
    Ok(())
}

/// The `case` coordinate, each case's status and the swept keys' values; the swept keys' short
/// names as CF auxiliary coordinates.
fn write_cases(
    w: &mut FileWriter,
    root: &h5::Group,
    cases: &[ManifestCase],
    statuses: &[String],
    keys: &[String],
) -> Result<(h5::Dataset, String), OutputError> {
    let names: Vec<String> = cases.iter().map(|c| c.name.clone()).collect();
    let case = w.string_coordinate(root, "case", &names, "case name")?;
    // CF auxiliary coordinates: xarray makes the swept keys coordinates of every variable
    // along `case`, so `.set_xindex("radial_clearance_m").sel(radial_clearance_m=…)` works.
    let coordinates = keys
        .iter()
        .map(|k| k.rsplit('.').next().unwrap_or(k))
        .collect::<Vec<_>>()
        .join(" ");
    let status = w.string_variable(
        root,
        "status",
        statuses,
        &case,
        "ok, failed: why, or missing: why",
    )?;
    if !coordinates.is_empty() {
        w.str_attr(&status, "coordinates", &coordinates)?;
    }
    for (k, key) in keys.iter().enumerate() {
        let short = key.rsplit('.').next().unwrap_or(key);
        let values: Vec<f64> = cases
            .iter()
            .map(|c| c.parameters.get(k).map_or(f64::NAN, |p| p.1))
            .collect();
        let ds = w.variable(root, short, &values, &[&case])?;
        w.str_attr(&ds, "long_name", &format!("swept case-file key {key}"))?;
        w.str_attr(&ds, "sweep_key", key)?;
        w.str_attr(&ds, "units", "as in the case file (the key's suffix)")?;
    }
    Ok((case, coordinates))
}

/// Each summary row over (case, method).
fn write_summary_rows(
    w: &mut FileWriter,
    root: &h5::Group,
    rows: &BTreeMap<&str, (&str, &str)>,
    numbers: &[Option<CaseNumbers>],
    dims: [&h5::Dataset; 2],
    coordinates: &str,
) -> Result<(), OutputError> {
    for (name, (units, long)) in rows {
        let mut a = Array2::from_elem((numbers.len(), 2), f64::NAN);
        for (i, c) in numbers.iter().enumerate() {
            if let Some((_, _, v)) = c.as_ref().and_then(|c| c.summary.get(*name)) {
                a[[i, 0]] = v[0];
                a[[i, 1]] = v[1];
            }
        }
        let ds = w.variable_2d(root, name, &a, dims, units, long)?;
        if !coordinates.is_empty() {
            w.str_attr(&ds, "coordinates", coordinates)?;
        }
    }
    Ok(())
}

/// Each series over (case, crank angle); a case sampled at other crank angles stays NaN.
fn write_series(
    w: &mut FileWriter,
    root: &h5::Group,
    series: &BTreeMap<(&str, &str), (&str, &str)>,
    numbers: &[Option<CaseNumbers>],
    crank: &[f64],
    case: &h5::Dataset,
    coordinates: &str,
) -> Result<(), OutputError> {
    let ca = crate::output::layout::CRANK_ANGLE;
    let angle = w.coordinate(root, ca.name, crank, ca.units, ca.long_name)?;
    for ((m, s), (units, long)) in series {
        let mut a = Array2::from_elem((numbers.len(), crank.len()), f64::NAN);
        for (i, c) in numbers.iter().enumerate() {
            if let Some((_, _, angles, v)) = c
                .as_ref()
                .and_then(|c| c.series.get(&(m.to_string(), s.to_string())))
                && angles == crank
            {
                a.row_mut(i).assign(&ndarray::ArrayView1::from(&v[..]));
            }
        }
        let ds = w.variable_2d(
            root,
            &format!("{m}_{s}"),
            &a,
            [case, &angle],
            units,
            &format!("{m}: {long}"),
        )?;
        if !coordinates.is_empty() {
            w.str_attr(&ds, "coordinates", coordinates)?;
        }
    }
    Ok(())
}
