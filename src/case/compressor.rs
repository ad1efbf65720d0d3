//! The compressor machine file (`cases/compressor_machine.toml`) and `jbearing synth-loads`,
//! which turns it into the load, speed and feed tables of the two compressor cases through
//! [`jbearing_solvers::slider_crank`].
//!
//! ```text
//!   compressor_machine.toml ──► SliderCrankParams ──tabulate(n)──►
//!       compressor_main_load.csv   crank_angle_deg, load_x_n, load_y_n          (machine frame)
//!       compressor_rod_load.csv    crank_angle_deg, load_x_n, load_y_n          (rod frame)
//!       compressor_rod_speed.csv   crank_angle_deg, journal_speed_rad_s, bearing_speed_rad_s
//!       compressor_rod_feed.csv    crank_angle_deg, feed_pressure_pa
//! ```

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Deserialize;

use jbearing_solvers::slider_crank::{CrankDrilling, SliderCrankParams, SliderCrankState};

use super::units::{deg_to_rad, rpm_to_rad_s};
use super::{CaseError, Ctx};

/// The machine file as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompressorFile {
    pub version: i64,
    pub bore_m: f64,
    pub stroke_m: f64,
    pub rod_length_m: f64,
    pub crank_speed_rpm: f64,
    pub reciprocating_mass_kg: f64,
    pub rotating_mass_kg: f64,
    pub counterweight_fraction: f64,
    pub main_bearing_count: f64,
    pub suction_pressure_pa_abs: f64,
    pub discharge_pressure_pa_abs: f64,
    pub crankcase_pressure_pa_abs: f64,
    pub clearance_volume_fraction: f64,
    pub polytropic_exponent: f64,
    pub drilling: DrillingSection,
    pub tables: TablesSection,
}

/// `[drilling]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DrillingSection {
    pub main_journal_radius_m: f64,
    pub inlet_angle_deg: f64,
    pub hole_diameter_m: f64,
    pub main_groove_center_deg: f64,
    pub main_groove_length_m: f64,
    pub outlet_radius_m: f64,
    pub main_feed_pressure_pa: f64,
    pub oil_density_kg_m3: f64,
    pub cavitation_pressure_pa: f64,
}

/// `[tables]`: what to write.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TablesSection {
    pub points_per_revolution: usize,
    pub main_load: String,
    pub rod_load: String,
    pub rod_speed: String,
    pub rod_feed: String,
}

/// The machine, resolved.
#[derive(Debug, Clone)]
pub struct Compressor {
    /// The model's parameters.
    pub params: SliderCrankParams,
    /// Points per revolution of the tables.
    pub points: usize,
    /// Output paths (absolute or relative to the current directory), in the order
    /// main load, rod load, rod speed, rod feed.
    pub tables: [PathBuf; 4],
}

impl Compressor {
    /// Read the machine file.
    pub fn from_file(path: &Path) -> Result<Self, CaseError> {
        let text = std::fs::read_to_string(path).map_err(|source| CaseError::Read {
            file: path.to_path_buf(),
            source,
        })?;
        let ctx = Ctx::new(&text, path);
        let raw: CompressorFile = ctx.parse()?;
        if raw.version != 1 {
            return Err(ctx.err("version", format!("expected 1, got {}", raw.version)));
        }
        let d = &raw.drilling;
        let params = SliderCrankParams {
            bore: raw.bore_m,
            stroke: raw.stroke_m,
            rod_length: raw.rod_length_m,
            crank_speed: rpm_to_rad_s(raw.crank_speed_rpm),
            reciprocating_mass: raw.reciprocating_mass_kg,
            rotating_mass: raw.rotating_mass_kg,
            counterweight_fraction: raw.counterweight_fraction,
            main_bearing_count: raw.main_bearing_count,
            suction_pressure: raw.suction_pressure_pa_abs,
            discharge_pressure: raw.discharge_pressure_pa_abs,
            crankcase_pressure: raw.crankcase_pressure_pa_abs,
            clearance_volume_fraction: raw.clearance_volume_fraction,
            polytropic_exponent: raw.polytropic_exponent,
            drilling: CrankDrilling {
                main_journal_radius: d.main_journal_radius_m,
                inlet_angle: deg_to_rad(d.inlet_angle_deg),
                hole_diameter: d.hole_diameter_m,
                groove_center: deg_to_rad(d.main_groove_center_deg),
                groove_length: d.main_groove_length_m,
                outlet_radius: d.outlet_radius_m,
                main_feed_pressure: d.main_feed_pressure_pa,
                oil_density: d.oil_density_kg_m3,
                cavitation_pressure: d.cavitation_pressure_pa,
            },
        };
        if let Err(jbearing_solvers::slider_crank::SliderCrankError::InvalidParameter {
            name,
            value,
            requirement,
        }) = params.validate()
        {
            // The model's names are the file's keys without their unit suffix.
            let key = key_of(name);
            return Err(ctx.err(&key, format!("{value} must be {requirement}")));
        }
        let t = &raw.tables;
        if t.points_per_revolution < 36 {
            return Err(ctx.err(
                "tables.points_per_revolution",
                format!("{} is too few (at least 36)", t.points_per_revolution),
            ));
        }
        Ok(Self {
            params,
            points: t.points_per_revolution,
            tables: [
                ctx.relative(&t.main_load),
                ctx.relative(&t.rod_load),
                ctx.relative(&t.rod_speed),
                ctx.relative(&t.rod_feed),
            ],
        })
    }

    /// The states at the table points.
    pub fn states(&self) -> Vec<SliderCrankState> {
        self.params
            .tabulate(self.points)
            .expect("validated when the file was read")
    }

    /// Write the four tables; returns their paths.
    pub fn write_tables(&self) -> std::io::Result<Vec<PathBuf>> {
        let states = self.states();
        let header = "# written by `jbearing synth-loads` from the slider-crank model \
                      (jbearing_solvers::slider_crank); see cases/README.md\n";
        let mut main = format!("{header}crank_angle_deg,load_x_n,load_y_n\n");
        let mut rod = format!(
            "{header}# rod-bearing frame: x along the rod from the big end to the small end\n\
             crank_angle_deg,load_x_n,load_y_n\n"
        );
        let mut speed =
            format!("{header}crank_angle_deg,journal_speed_rad_s,bearing_speed_rad_s\n");
        let mut feed = format!("{header}crank_angle_deg,feed_pressure_pa\n");
        for s in &states {
            let a = s.crank_angle.to_degrees();
            let _ = writeln!(main, "{a:.3},{:.6e},{:.6e}", s.main_load[0], s.main_load[1]);
            let _ = writeln!(rod, "{a:.3},{:.6e},{:.6e}", s.rod_load[0], s.rod_load[1]);
            let _ = writeln!(
                speed,
                "{a:.3},{:.9e},{:.9e}",
                self.params.crank_speed, s.rod_bearing_speed
            );
            let _ = writeln!(feed, "{a:.3},{:.6e}", s.rod_feed_pressure);
        }
        for (path, text) in self.tables.iter().zip([main, rod, speed, feed]) {
            if let Some(dir) = path.parent()
                && !dir.as_os_str().is_empty()
            {
                std::fs::create_dir_all(dir)?;
            }
            // Atomically, like every result file: a table is the old one or the complete new
            // one, never half written.
            crate::output::write_atomically(path, |tmp| {
                std::fs::write(tmp, &text).map_err(|source| crate::output::OutputError::Io {
                    action: "writing",
                    path: path.clone(),
                    source,
                })
            })
            .map_err(std::io::Error::other)?;
        }
        Ok(self.tables.to_vec())
    }
}

/// The machine-file key of a slider-crank parameter name.
fn key_of(name: &str) -> String {
    match name {
        "bore" | "stroke" | "rod_length" => format!("{name}_m"),
        "crank_speed" => "crank_speed_rpm".into(),
        "reciprocating_mass" | "rotating_mass" => format!("{name}_kg"),
        "suction_pressure" | "discharge_pressure" | "crankcase_pressure" => {
            format!("{name}_pa_abs")
        }
        "main_journal_radius" | "hole_diameter" | "outlet_radius" => format!("drilling.{name}_m"),
        "groove_length" => "drilling.main_groove_length_m".into(),
        "groove_center" => "drilling.main_groove_center_deg".into(),
        "inlet_angle" => "drilling.inlet_angle_deg".into(),
        "oil_density" => "drilling.oil_density_kg_m3".into(),
        "main_feed_pressure" | "cavitation_pressure" => format!("drilling.{name}_pa"),
        other => other.to_string(),
    }
}
