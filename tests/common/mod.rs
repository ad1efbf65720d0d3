//! Writer test fixture: a `CaseReport` filled from closed forms, NOT from the solvers.
//!
//! It exists so that the output writers (HDF5, VTKHDF, plots, CSV) can be tested before and
//! independently of the numerics, on data with the right shapes, units and orders of magnitude.
//! The "rigorous" fields are the quasi-static short-bearing (Ocvirk) pressure with the Gumbel
//! (half-film) condition for a journal whose eccentricity vector is prescribed over the crank
//! cycle; the loads are the integral of that pressure; the "mobility" series are the same
//! closed forms at a 10 % smaller eccentricity ratio. None of it is a solution of the dynamic
//! inverse problem; it only has to be physically plausible and exactly known.
//!
//! Closed forms used (bearing frame, θ from +x, h = c − e_x cos θ − e_y sin θ = c(1 − ε cos(θ−ψ))):
//!
//! ```text
//!   p(θ, z)   = max(0, 3 μ U c ε sin(θ − ψ) (z² − L²/4) / (R h³))        Ocvirk, U = R ω
//!   W         = ∫∫ p (cos θ, sin θ) R dθ dz        (load on the journal, balances the film)
//!   h_min     = c (1 − ε)
//!   Q_side    = U c L ε                            (short bearing, half film)
//!   P_loss    = 2π μ U² R L / (c √(1 − ε²))        (Couette dissipation of a full film)
//! ```

#![allow(dead_code)]

use std::f64::consts::{PI, TAU};

use jbearing::output::{
    CaseReport, Field, FieldSnapshots, Geometry, InputFile, Method, MethodResult, Parameter,
    ParameterValue, Reduction, RunInfo, Series, SummaryRow, names,
};
use ndarray::Array3;

pub const RADIUS: f64 = 0.02743;
pub const LENGTH: f64 = 0.018288;
pub const CLEARANCE: f64 = 48.9e-6;
pub const VISCOSITY: f64 = 0.02;
pub const SPEED_RPM: f64 = 1800.0;
pub const FEED_PRESSURE: f64 = 0.2068e6;
pub const N_SAMPLES: usize = 73; // every 5° of crank angle, 0 … 360 inclusive
pub const N_THETA: usize = 48;
pub const N_Z: usize = 9;
pub const N_INSTANTS: usize = 7; // every 60°

pub fn omega() -> f64 {
    SPEED_RPM * TAU / 60.0
}

/// Prescribed journal motion over the crank cycle φ ∈ [0°, 360°].
pub fn eccentricity(crank_deg: f64, scale: f64) -> (f64, f64) {
    let phi = crank_deg.to_radians();
    let eps = scale * (0.55 + 0.25 * (phi - 0.3).sin());
    let psi = 1.2 * PI + 0.4 * phi.cos();
    (eps, psi)
}

pub fn pressure(eps: f64, psi: f64, theta: f64, z: f64) -> f64 {
    let u = RADIUS * omega();
    let h = CLEARANCE * (1.0 - eps * (theta - psi).cos());
    let p = 3.0
        * VISCOSITY
        * u
        * CLEARANCE
        * eps
        * (theta - psi).sin()
        * (z * z - LENGTH * LENGTH / 4.0)
        / (RADIUS * h.powi(3));
    p.max(0.0)
}

/// Load on the journal by trapezoidal integration of the fixture pressure on a fine grid.
pub fn load(eps: f64, psi: f64) -> (f64, f64) {
    let (nt, nz) = (720, 41);
    let (dth, dz) = (TAU / nt as f64, LENGTH / (nz - 1) as f64);
    let (mut wx, mut wy) = (0.0, 0.0);
    for i in 0..nt {
        let th = i as f64 * dth;
        for j in 0..nz {
            let z = -LENGTH / 2.0 + j as f64 * dz;
            let w = if j == 0 || j == nz - 1 { 0.5 } else { 1.0 };
            let p = pressure(eps, psi, th, z) * w * RADIUS * dth * dz;
            wx += p * th.cos();
            wy += p * th.sin();
        }
    }
    (wx, wy)
}

pub fn theta_grid() -> Vec<f64> {
    (0..N_THETA)
        .map(|i| i as f64 * TAU / N_THETA as f64)
        .collect()
}

pub fn z_grid() -> Vec<f64> {
    (0..N_Z)
        .map(|j| -LENGTH / 2.0 + j as f64 * LENGTH / (N_Z - 1) as f64)
        .collect()
}

fn method_result(method: Method, scale: f64, with_fields: bool) -> MethodResult {
    let period = 60.0 / SPEED_RPM;
    let crank: Vec<f64> = (0..N_SAMPLES).map(|k| 5.0 * k as f64).collect();
    let time: Vec<f64> = crank.iter().map(|c| c / 360.0 * period).collect();
    let u = RADIUS * omega();
    let mut s: Vec<Vec<f64>> = vec![Vec::new(); 11];
    for &c in &crank {
        let (eps, psi) = eccentricity(c, scale);
        let (wx, wy) = load(eps, psi);
        s[0].push(wx);
        s[1].push(wy);
        s[2].push(FEED_PRESSURE);
        s[3].push(CLEARANCE * eps * psi.cos());
        s[4].push(CLEARANCE * eps * psi.sin());
        s[5].push(eps);
        s[6].push(CLEARANCE * (1.0 - eps));
        s[7].push(u * CLEARANCE * LENGTH * eps);
        s[8].push(u * CLEARANCE * LENGTH * eps);
        s[9].push(
            TAU * VISCOSITY * u * u * RADIUS * LENGTH / (CLEARANCE * (1.0 - eps * eps).sqrt()),
        );
        s[10].push(psi);
    }
    let meta = [
        (names::LOAD_X, "load on the journal, x component", "N"),
        (names::LOAD_Y, "load on the journal, y component", "N"),
        (names::FEED_PRESSURE, "feed pressure", "Pa"),
        (names::ECCENTRICITY_X, "journal centre, x", "m"),
        (names::ECCENTRICITY_Y, "journal centre, y", "m"),
        (names::ECCENTRICITY_RATIO, "eccentricity ratio", "1"),
        (names::MIN_FILM_THICKNESS, "minimum film thickness", "m"),
        (names::SUPPLY_FLOW, "supply flow", "m3 s-1"),
        (names::SIDE_LEAKAGE, "side leakage", "m3 s-1"),
        (names::POWER_LOSS, "power loss", "W"),
        (
            names::ATTITUDE_ANGLE,
            jbearing::run::ATTITUDE_LONG_NAME,
            "rad",
        ),
    ];
    let series = meta
        .iter()
        .zip(s)
        .map(|((n, l, u), v)| Series::new(n, l, u, v))
        .collect();
    let fields = with_fields.then(|| {
        let icrank: Vec<f64> = (0..N_INSTANTS).map(|k| 60.0 * k as f64).collect();
        let itime: Vec<f64> = icrank.iter().map(|c| c / 360.0 * period).collect();
        let (theta, z) = (theta_grid(), z_grid());
        let mut p = Array3::zeros((N_INSTANTS, N_THETA, N_Z));
        let mut h = Array3::zeros((N_INSTANTS, N_THETA, N_Z));
        // Film content: full film (1) where the half film carries pressure, else a film
        // fraction falling with the gap, h_min / h.
        let mut content = Array3::zeros((N_INSTANTS, N_THETA, N_Z));
        for (k, &c) in icrank.iter().enumerate() {
            let (eps, psi) = eccentricity(c, scale);
            for (i, &th) in theta.iter().enumerate() {
                for (j, &zz) in z.iter().enumerate() {
                    p[[k, i, j]] = pressure(eps, psi, th, zz);
                    h[[k, i, j]] = CLEARANCE * (1.0 - eps * (th - psi).cos());
                    content[[k, i, j]] = if p[[k, i, j]] > 0.0 {
                        1.0
                    } else {
                        (1.0 - eps) / (1.0 - eps * (th - psi).cos())
                    };
                }
            }
        }
        FieldSnapshots {
            time: itime,
            crank_angle: icrank,
            theta,
            z,
            fields: vec![
                Field {
                    name: names::PRESSURE.into(),
                    long_name: "film pressure (gauge)".into(),
                    units: "Pa".into(),
                    values: p,
                },
                Field {
                    name: names::FILM_THICKNESS.into(),
                    long_name: "film thickness".into(),
                    units: "m".into(),
                    values: h,
                },
                Field {
                    name: names::FILM_CONTENT.into(),
                    long_name: "film content".into(),
                    units: "1".into(),
                    values: content,
                },
            ],
        }
    });
    MethodResult {
        method,
        time,
        crank_angle: crank,
        series,
        fields,
        period: None,
        solver_info: vec![
            ("cycles".into(), ParameterValue::Integer(3)),
            (
                "fixture".into(),
                ParameterValue::Text("writer test fixture".into()),
            ),
        ],
    }
}

/// The fixture report (see the module documentation).
pub fn report(case_name: &str) -> CaseReport {
    let rig = method_result(Method::Rigorous, 1.0, true);
    let mob = method_result(Method::Mobility, 0.9, false);
    let both = [rig.clone(), mob.clone()];
    let summary = vec![
        SummaryRow::from_series(
            &both,
            names::MIN_FILM_THICKNESS,
            Reduction::Min,
            "min_film_thickness_min",
            "cycle minimum of h_min",
        ),
        SummaryRow::from_series(
            &both,
            names::SUPPLY_FLOW,
            Reduction::Mean,
            "supply_flow_mean",
            "cycle mean supply flow",
        ),
        SummaryRow::from_series(
            &both,
            names::POWER_LOSS,
            Reduction::Mean,
            "power_loss_mean",
            "cycle mean power loss",
        ),
        SummaryRow {
            name: "max_pressure_max".into(),
            long_name: "cycle maximum of the peak pressure".into(),
            units: "Pa".into(),
            rigorous: Some(1.0e7),
            mobility: None,
        },
    ];
    CaseReport {
        case_name: case_name.into(),
        case_text: "# writer test fixture\nversion = 1\n[bearing]\nradius = 0.02743 # m\n".into(),
        case_path: None,
        input_files: vec![InputFile {
            path: "loads/fixture.csv".into(),
            text: "crank_angle_deg,load_x_N,load_y_N\n0,0,-1000\n".into(),
        }],
        geometry: Geometry {
            radius: RADIUS,
            length: LENGTH,
            radial_clearance: CLEARANCE,
        },
        parameters: vec![
            Parameter::number("radius", RADIUS, "m", "bearing radius"),
            Parameter::number("viscosity", VISCOSITY, "Pa s", "dynamic viscosity"),
            Parameter::number("speed", omega(), "rad s-1", "journal angular speed"),
            Parameter::integer("n_theta", N_THETA as i64, "circumferential nodes"),
            Parameter::text(
                "cavitation_model",
                "fixture (Gumbel half film)",
                "cavitation model",
            ),
            Parameter::flag("run_in", true, "run-in procedure used"),
        ],
        run: RunInfo {
            jbearing_version: env!("CARGO_PKG_VERSION").into(),
            git_commit: "fixture".into(),
            wall_time: 1.25,
            started_utc: "2026-11-22T05:00:00Z".into(),
        },
        methods: vec![rig, mob],
        summary,
        closed_form: None,
        elastic: None,
        warnings: Vec::new(),
    }
}

/// A small grooved bearing (R 25 mm, L 20 mm, c 40 µm, one feed groove) under a rotating load
/// at 1800 rpm: the case text with the `[lubricant]` body `lubricant` and the tables `tail`
/// after the load.
pub fn small_bearing_case(name: &str, lubricant: &str, tail: &str) -> String {
    format!(
        r#"version = 1
name = "{name}"

[bearing]
radius_m = 0.025
length_m = 0.02
radial_clearance_m = 4e-5

[[grooves]]
center_angle_deg = 90.0
circumferential_length_m = 0.006
axial_width_m = 0.006

{lubricant}

[operation]
cycle_deg = 360.0
crank_speed_rpm = 1800.0

[load]
crank_angle_deg = [0.0, 90.0, 180.0, 270.0]
x_n = [-2000.0, -1500.0, -1000.0, -1500.0]
y_n = [0.0, 500.0, 0.0, -500.0]

{tail}"#
    )
}

/// A cheap swept case: Booker's mobility method on [`small_bearing_case`], 3 clearances × 2
/// viscosities = 6 cases.
pub fn sweep_case(dir: &std::path::Path) -> std::path::PathBuf {
    let p = dir.join("sweep.toml");
    let tail = r#"[solver]
mobility_model = "booker"

[output]
samples_per_cycle = 72
plots = false

[methods]
rigorous = false
mobility = true

[sweep]
combine = "factorial"
[sweep.values]
"bearing.radial_clearance_m" = [3e-5, 4e-5, 5e-5]
"lubricant.viscosity_pa_s" = { start = 0.01, stop = 0.04, count = 2, spacing = "log" }
"#;
    std::fs::write(
        &p,
        small_bearing_case("sw", "[lubricant]\nviscosity_pa_s = 0.02", tail),
    )
    .unwrap();
    p
}

/// The package root (case files are named relative to it).
pub fn root() -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// `jbearing ARGS…` run from the package root, without colour or a RUST_LOG of the caller's.
pub fn jbearing(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_jbearing"))
        .args(args)
        .current_dir(root())
        .env("NO_COLOR", "1")
        .env_remove("RUST_LOG")
        .output()
        .expect("run jbearing")
}

/// A process's output as text.
pub fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// The RGB pixels of a PNG, row by row.
pub fn png_pixels(path: &std::path::Path) -> (u32, u32, Vec<[u8; 3]>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let step = info.color_type.samples();
    let pixels = buf[..info.buffer_size()]
        .chunks(step)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    (info.width, info.height, pixels)
}

/// Pixels of exactly `rgb` in the rows `rows` of an image.
pub fn count_color(path: &std::path::Path, rgb: [u8; 3], rows: std::ops::Range<u32>) -> usize {
    let (w, _, px) = png_pixels(path);
    px.iter()
        .enumerate()
        .filter(|(k, p)| rows.contains(&((*k as u32) / w)) && **p == rgb)
        .count()
}
