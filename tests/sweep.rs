//! Sweeps, shards and merges end to end (issue 18): a `[sweep]` case expands into named cases;
//! four shards run as separate processes at once (the GNU parallel / job-array form) and their
//! merge equals the merge of one unsharded batch bit for bit; a re-run resumes (skips what
//! exists) unless forced; a missing shard is listed, never dropped.

use std::path::Path;
use std::process::Command;

mod common;
use common::{jbearing, sweep_case, text};

/// Every dataset of an HDF5 file (recursively): name → raw bytes of its values.
fn contents(path: &Path) -> Vec<(String, Vec<u8>)> {
    let f = hdf5_metno::File::open(path).unwrap();
    let mut out = Vec::new();
    for name in f.member_names().unwrap() {
        let ds = f.dataset(&name).unwrap();
        let bytes = if let Ok(v) = ds.read_raw::<f64>() {
            v.iter().flat_map(|x| x.to_bits().to_le_bytes()).collect()
        } else {
            let v: Vec<hdf5_metno::types::VarLenUnicode> = ds.read_raw().unwrap();
            v.iter()
                .flat_map(|s| s.as_str().as_bytes().to_vec())
                .collect()
        };
        out.push((name, bytes));
    }
    out.sort();
    out
}

#[test]
fn sharded_batch_merges_to_the_unsharded_one_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let case = sweep_case(dir.path());
    let c = case.to_str().unwrap();

    let check = jbearing(&["check", c]);
    assert!(check.status.success(), "{}", text(&check.stderr));
    assert!(
        text(&check.stdout)
            .contains("sweep of 6 cases over bearing.radial_clearance_m, lubricant.viscosity_pa_s"),
        "{}",
        text(&check.stdout)
    );
    // A single run refuses a sweep file.
    let run = jbearing(&["run", c, "--out", dir.path().join("x").to_str().unwrap()]);
    assert!(!run.status.success());
    assert!(
        text(&run.stderr).contains("jbearing batch"),
        "{}",
        text(&run.stderr)
    );

    // One batch.
    let whole = dir.path().join("whole");
    let w = whole.to_str().unwrap();
    let out = jbearing(&["batch", c, "--out", w, "--no-progress"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(whole.join("shard_0_of_1.json").is_file());
    assert!(whole.join("batch_summary.csv").is_file());
    let a = dir.path().join("a.nc");
    let m = jbearing(&["merge", w, "--out", a.to_str().unwrap()]);
    assert!(m.status.success(), "{}", text(&m.stderr));

    // Four shards at once, as separate processes (what GNU parallel or a job array does).
    let sharded = dir.path().join("sharded");
    let s = sharded.to_str().unwrap().to_owned();
    let children: Vec<_> = (0..4)
        .map(|i| {
            Command::new(env!("CARGO_BIN_EXE_jbearing"))
                .args([
                    "batch",
                    c,
                    "--shard",
                    &format!("{i}/4"),
                    "--out",
                    &s,
                    "--no-progress",
                ])
                .env("NO_COLOR", "1")
                .output()
        })
        .collect();
    for (i, ch) in children.into_iter().enumerate() {
        let o = ch.unwrap();
        assert!(o.status.success(), "shard {i}: {}", text(&o.stderr));
    }
    for i in 0..4 {
        assert!(sharded.join(format!("shard_{i}_of_4.json")).is_file());
    }
    let b = dir.path().join("b.nc");
    let m = jbearing(&["merge", &s, "--out", b.to_str().unwrap()]);
    assert!(m.status.success(), "{}", text(&m.stderr));
    assert!(
        text(&m.stdout).contains("6 cases, 6 ok"),
        "{}",
        text(&m.stdout)
    );

    let (ca, cb) = (contents(&a), contents(&b));
    assert_eq!(
        ca.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>(),
        cb.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>()
    );
    for ((name, x), (_, y)) in ca.iter().zip(&cb) {
        assert!(
            x == y,
            "{name} differs between the sharded and the whole batch"
        );
    }
    // The sweep's coordinates and the cases' numbers are there.
    let f = hdf5_metno::File::open(&a).unwrap();
    let clearance: Vec<f64> = f.dataset("radial_clearance_m").unwrap().read_raw().unwrap();
    assert_eq!(clearance, [3e-5, 3e-5, 4e-5, 4e-5, 5e-5, 5e-5]);
    let h: Vec<f64> = f
        .dataset("min_film_thickness_min")
        .unwrap()
        .read_raw()
        .unwrap();
    assert_eq!(h.len(), 12);
    // Mobility column (index 1) finite, rigorous (not asked for) NaN; the more viscous oil
    // carries the load on a thicker film at the same clearance.
    assert!(h.chunks(2).all(|r| r[0].is_nan() && r[1].is_finite()));
    assert!(
        h[3] > h[1],
        "μ 0.04 vs 0.01 at c = 30 µm: {} vs {}",
        h[3],
        h[1]
    );

    // Resume: a re-run of shard 0 skips its cases; --force recomputes them.
    let again = jbearing(&["batch", c, "--shard", "0/4", "--out", &s, "--no-progress"]);
    assert!(again.status.success());
    let said = text(&again.stdout);
    let mine = said.matches("skipped:").count();
    let manifest = std::fs::read_to_string(sharded.join("shard_0_of_4.json")).unwrap();
    assert_eq!(mine, manifest.matches("\"status\": \"skipped\"").count());
    assert!(
        mine >= 1,
        "shard 0 holds at least one of 6 cases here: {said}"
    );
    let forced = jbearing(&[
        "batch",
        c,
        "--shard",
        "0/4",
        "--out",
        &s,
        "--no-progress",
        "--force",
    ]);
    assert!(forced.status.success());
    assert_eq!(text(&forced.stdout).matches("skipped:").count(), 0);

    // A missing shard is listed and makes the merge fail, with the file still written.
    std::fs::remove_file(sharded.join("shard_3_of_4.json")).unwrap();
    let c_nc = dir.path().join("c.nc");
    let m = jbearing(&["merge", &s, "--out", c_nc.to_str().unwrap()]);
    assert!(!m.status.success());
    let err = text(&m.stderr);
    assert!(
        err.contains("missing: shard 3 of 4 has no manifest"),
        "{err}"
    );
    let f = hdf5_metno::File::open(&c_nc).unwrap();
    let status: Vec<hdf5_metno::types::VarLenUnicode> =
        f.dataset("status").unwrap().read_raw().unwrap();
    let missing = status
        .iter()
        .filter(|s| s.as_str().starts_with("missing"))
        .count();
    assert!(
        missing >= 1 && missing == err.matches(": missing:").count(),
        "{err}"
    );
}

#[test]
fn bad_shard_arguments_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let case = sweep_case(dir.path());
    for bad in ["4/4", "1", "a/2", "0/0"] {
        let o = jbearing(&[
            "batch",
            case.to_str().unwrap(),
            "--shard",
            bad,
            "--out",
            dir.path().to_str().unwrap(),
        ]);
        assert!(!o.status.success(), "{bad}");
        assert!(
            text(&o.stderr).contains("--shard"),
            "{bad}: {}",
            text(&o.stderr)
        );
    }
}

/// A batch of a bearing sweep (6 cases) and a mechanism case over two shards: every case runs
/// in exactly one shard (the mechanism case by its name too), the summaries and manifests
/// list it there, and the merge lists all seven, the mechanism case as not merged.
#[test]
fn mechanism_cases_are_jobs_of_a_sharded_batch() {
    let dir = tempfile::tempdir().unwrap();
    let cases = dir.path().join("cases");
    std::fs::create_dir(&cases).unwrap();
    sweep_case(&cases);
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mech = std::fs::read_to_string(root.join("cases/flores2009_slider_crank.toml"))
        .unwrap()
        .replace("name = \"flores2009_slider_crank\"", "name = \"crank\"")
        .replace("turns = 2", "turns = 1\nplots = false");
    assert!(mech.contains("plots = false"));
    std::fs::write(cases.join("crank.toml"), mech).unwrap();
    let out = dir.path().join("out");
    let (c, o) = (cases.to_str().unwrap(), out.to_str().unwrap());
    let mut ran = std::collections::HashMap::<String, usize>::new();
    for i in 0..2 {
        let shard = format!("{i}/2");
        let r = jbearing(&["batch", c, "--shard", &shard, "--out", o, "--no-progress"]);
        assert!(r.status.success(), "shard {i}: {}", text(&r.stderr));
        let manifest: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(out.join(format!("shard_{i}_of_2.json"))).unwrap(),
        )
        .unwrap();
        let list = manifest["cases"].as_array().unwrap();
        assert_eq!(list.len(), 7, "every case of the batch in each manifest");
        let csv = std::fs::read_to_string(out.join(format!("shard_{i}_of_2_summary.csv"))).unwrap();
        for case in list {
            let name = case["name"].as_str().unwrap();
            let kind = case["kind"].as_str().unwrap();
            assert_eq!(kind == "mechanism", name == "crank", "{name}: kind {kind}");
            match case["status"].as_str().unwrap() {
                "ok" => {
                    assert_eq!(case["shard"].as_u64(), Some(i));
                    *ran.entry(name.to_string()).or_default() += 1;
                    assert!(
                        csv.lines().any(|l| l.starts_with(&format!("{name},ok,"))),
                        "{name} has no row in shard {i}: {csv}"
                    );
                }
                "other shard" => {
                    assert_ne!(case["shard"].as_u64(), Some(i));
                    assert!(!csv.lines().any(|l| l.starts_with(&format!("{name},"))));
                }
                s => panic!("{name}: status {s}"),
            }
        }
    }
    assert_eq!(ran.len(), 7, "{ran:?}");
    assert!(ran.values().all(|&n| n == 1), "{ran:?}");
    // The mechanism case's row: h_min and ε_max in the bearing columns, the peak force named.
    let csvs: String = (0..2)
        .map(|i| std::fs::read_to_string(out.join(format!("shard_{i}_of_2_summary.csv"))).unwrap())
        .collect();
    let row = csvs
        .lines()
        .find(|l| l.starts_with("crank,ok,mechanism:lubricated,"))
        .expect("mechanism row");
    let cells: Vec<&str> = row.split(',').collect();
    let h: f64 = cells[3].parse().unwrap();
    assert!(h > 0.0 && h < 0.2e-3, "h_min {h}");
    let eps: f64 = cells[6].parse().unwrap();
    assert!(eps > 0.0 && eps < 1.0, "eps {eps}");
    assert!(row.contains("joint_force_max"), "{row}");
    // Resume: a re-run skips the mechanism case too.
    let again = jbearing(&["batch", c, "--shard", "0/2", "--out", o, "--no-progress"]);
    assert!(again.status.success());
    let again = jbearing(&["batch", c, "--shard", "1/2", "--out", o, "--no-progress"]);
    assert!(again.status.success());
    let skipped: usize = (0..2)
        .map(|i| {
            std::fs::read_to_string(out.join(format!("shard_{i}_of_2.json")))
                .unwrap()
                .matches("\"skipped\"")
                .count()
        })
        .sum();
    assert_eq!(skipped, 7);

    let nc = dir.path().join("all.nc");
    let m = jbearing(&["merge", o, "--out", nc.to_str().unwrap()]);
    assert!(m.status.success(), "{}", text(&m.stderr));
    assert!(
        text(&m.stdout).contains("7 cases, 7 ok"),
        "{}",
        text(&m.stdout)
    );
    let f = hdf5_metno::File::open(&nc).unwrap();
    let names: Vec<hdf5_metno::types::VarLenUnicode> =
        f.dataset("case").unwrap().read_raw().unwrap();
    let status: Vec<hdf5_metno::types::VarLenUnicode> =
        f.dataset("status").unwrap().read_raw().unwrap();
    let k = names
        .iter()
        .position(|n| n.as_str() == "crank")
        .expect("crank listed");
    assert_eq!(status[k].as_str(), "ok (mechanism case: not merged)");
    assert!(
        status
            .iter()
            .enumerate()
            .all(|(j, s)| j == k || s.as_str() == "ok"),
        "{status:?}"
    );
}
