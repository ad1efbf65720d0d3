//! The case file as written: serde structs, one per TOML table, unknown keys rejected.
//! `cases/README.md` documents every key; defaults are the functions at the bottom.

use serde::Deserialize;

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaseFile {
    /// Format version; this program reads 1.
    pub version: i64,
    /// Case name (default: the file's stem).
    pub name: Option<String>,
    /// One line of description.
    pub description: Option<String>,
    /// The bearing.
    pub bearing: BearingSection,
    /// Feed grooves, `[[grooves]]`.
    #[serde(default)]
    pub grooves: Vec<GrooveSection>,
    /// The lubricant.
    pub lubricant: LubricantSection,
    /// Cycle and speeds.
    pub operation: OperationSection,
    /// Load history.
    pub load: LoadSection,
    /// Feed pressure history.
    #[serde(default)]
    pub feed: FeedSection,
    /// Grid.
    #[serde(default)]
    pub grid: GridSection,
    /// Solver settings.
    #[serde(default)]
    pub solver: SolverSection,
    /// Output settings.
    #[serde(default)]
    pub output: OutputSection,
    /// What to compute.
    #[serde(default)]
    pub methods: MethodsSection,
    /// Closed-form static-equilibrium table, `[closed_form]`.
    pub closed_form: Option<ClosedFormSection>,
    /// Elastic shaft and housing coupled to the film, `[elastic]`.
    pub elastic: Option<ElasticSection>,
    /// A parameter sweep (`crate::sweep`): the file stands for many cases, which `batch` and
    /// `check` expand; a single case (`run`) refuses it.
    pub sweep: Option<toml::Table>,
}

/// `[closed_form]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClosedFormSection {
    /// `"all"` or a list of model names.
    #[serde(default = "default_closed_form_models")]
    pub models: ClosedFormModels,
}

/// `closed_form.models`: `"all"` or `["short_gumbel", …]`.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum ClosedFormModels {
    /// One name (`"all"` or a model).
    One(String),
    /// Model names.
    List(Vec<String>),
}

fn default_closed_form_models() -> ClosedFormModels {
    ClosedFormModels::One("all".into())
}

/// `[elastic]`: plane-strain elastic shaft and housing (`jbearing_solvers::elastic`) whose
/// deformation adds to the film thickness.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ElasticSection {
    /// Young's modulus E of shaft and housing, Pa.
    pub youngs_modulus_pa: f64,
    /// Poisson's ratio ν of shaft and housing.
    pub poisson_ratio: f64,
    /// Radius of the shaft's central hole (held radially), m.
    pub shaft_hole_radius_m: f64,
    /// Half-width of the square housing (outer edges fixed), m.
    pub housing_half_width_m: f64,
    /// Nodes around the film surface of both bodies.
    #[serde(default = "default_elastic_n_theta")]
    pub n_theta: usize,
    /// Element layers of the shaft from the journal surface to the hole (default: nearly
    /// square elements).
    pub shaft_layers: Option<usize>,
    /// Element layers of the housing from the bore to its edges (default: nearly square).
    pub housing_layers: Option<usize>,
    /// Coupling converged when |C p̄ − g| ≤ this × c at every surface node, in the steady solve
    /// and in every film step of a dynamic run. Absent: each its validated default, 1e-5 for
    /// the steady solve, and for the dynamic film what the rigorous method's force tolerance
    /// needs (`ElasticParams::dynamic_gap_tolerance_for`, 1e-8 at the default 1e-6).
    pub gap_tolerance: Option<f64>,
    /// Most coupling (deformation) iterations.
    #[serde(default = "default_elastic_max_iterations")]
    pub max_iterations: usize,
}

/// The library's defaults (`ElasticParams::steel`): 240 nodes around, 200 iterations, what the
/// JB1 validation converged with.
fn default_elastic_n_theta() -> usize {
    jbearing_solvers::elastic::ElasticParams::steel(1.0).n_theta
}
fn default_elastic_max_iterations() -> usize {
    jbearing_solvers::elastic::ElasticParams::steel(1.0).max_iterations
}

/// `[bearing]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BearingSection {
    pub radius_m: f64,
    pub length_m: f64,
    pub radial_clearance_m: f64,
}

/// `[[grooves]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GrooveSection {
    pub center_angle_deg: f64,
    #[serde(default)]
    pub axial_center_m: f64,
    pub circumferential_length_m: f64,
    pub axial_width_m: f64,
}

/// `[lubricant]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LubricantSection {
    /// Constant viscosity; absent when `vogel` gives μ(T).
    pub viscosity_pa_s: Option<f64>,
    /// Vogel's μ₀(T) = a exp(b / (T − c)) \[Benasciutti2012\].
    pub vogel: Option<VogelSection>,
    /// Barus pressure–viscosity coefficient α (1/Pa) of the rigorous film, with a Vogel law
    /// (\[Benasciutti2012\]: 1e-8 … 2e-8); default 0.
    #[serde(default)]
    pub pressure_viscosity_coefficient_per_pa: f64,
    /// A named oil (ISO VG 32 … 680) whose Vogel curve gives μ(T): instead of `vogel`.
    pub oil: Option<String>,
    /// The film temperature for `vogel` / `oil`, given.
    pub temperature: Option<TemperatureSection>,
    /// The film temperature for `vogel` / `oil`, from a heat balance (instead of
    /// `temperature`).
    pub heat_balance: Option<HeatBalanceSection>,
    #[serde(default = "default_bulk_modulus")]
    pub bulk_modulus_pa: f64,
    #[serde(default)]
    pub cavitation_pressure_pa: f64,
    #[serde(default)]
    pub ambient_pressure_pa: f64,
    #[serde(default = "default_starved_film_fraction")]
    pub starved_film_fraction: f64,
}

/// `[lubricant.vogel]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VogelSection {
    pub a_pa_s: f64,
    pub b_c: f64,
    pub c_c: f64,
}

/// `[lubricant.temperature]`: `mean_c`, or `inlet_c` and `outlet_c` (and `rise_span_deg`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TemperatureSection {
    pub mean_c: Option<f64>,
    pub inlet_c: Option<f64>,
    pub outlet_c: Option<f64>,
    #[serde(default = "default_rise_span_deg")]
    pub rise_span_deg: f64,
}

/// `[lubricant.heat_balance]`: the effective temperature from the cycle-mean power loss.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeatBalanceSection {
    /// Oil supply temperature T_in, °C.
    pub supply_temperature_c: f64,
    /// Share χ of the power loss conducted away through housing and shaft (0 … < 1).
    #[serde(default)]
    pub heat_to_housing_and_shaft: f64,
    /// ρ c_p of the oil, J/(m³ K).
    #[serde(default = "default_volumetric_heat_capacity")]
    pub volumetric_heat_capacity_j_m3_k: f64,
    /// Tolerance on |T_bal − T_eff|, K.
    #[serde(default = "default_heat_balance_tolerance")]
    pub tolerance_k: f64,
    /// Solves allowed per method.
    #[serde(default = "default_heat_balance_iterations")]
    pub max_iterations: usize,
}

fn default_volumetric_heat_capacity() -> f64 {
    jbearing_solvers::heat_balance::DIN_31652_VOLUMETRIC_HEAT_CAPACITY
}

fn default_heat_balance_tolerance() -> f64 {
    jbearing_solvers::heat_balance::HeatBalanceParams::default().tolerance
}

fn default_heat_balance_iterations() -> usize {
    jbearing_solvers::heat_balance::HeatBalanceParams::default().max_iterations
}

fn default_rise_span_deg() -> f64 {
    180.0
}

/// `[operation]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OperationSection {
    pub cycle_deg: f64,
    pub crank_speed_rpm: f64,
    pub journal_speed_rpm: Option<f64>,
    pub bearing_speed_rpm: Option<f64>,
    pub speed_file: Option<String>,
}

/// `[load]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSection {
    pub file: Option<String>,
    pub crank_angle_deg: Option<Vec<f64>>,
    pub x_n: Option<Vec<f64>>,
    pub y_n: Option<Vec<f64>>,
    pub magnitude_n: Option<Vec<f64>>,
    pub direction: Option<[f64; 2]>,
    #[serde(default = "default_interpolation")]
    pub interpolation: String,
}

/// `[feed]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FeedSection {
    pub pressure_pa: Option<f64>,
    pub file: Option<String>,
    pub crank_angle_deg: Option<Vec<f64>>,
    pub pressure_history_pa: Option<Vec<f64>>,
}

/// `[grid]`: either key left out takes the library's validated default grid of the bearing's
/// L/D (`GridParams::for_length_ratio`: 120 × 31, or 160 × 23 below L/D = 1/4) — what the
/// application runs by default is what the validation tests run.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridSection {
    pub n_theta: Option<usize>,
    pub n_z: Option<usize>,
}

impl GridSection {
    /// The grid of a bearing with length ratio L/D: the keys given, the default for the rest.
    pub fn resolve(&self, length_over_diameter: f64) -> jbearing_solvers::reynolds::GridParams {
        let default =
            jbearing_solvers::reynolds::GridParams::for_length_ratio(length_over_diameter);
        jbearing_solvers::reynolds::GridParams {
            n_theta: self.n_theta.unwrap_or(default.n_theta),
            n_z: self.n_z.unwrap_or(default.n_z),
        }
    }
}

/// `[solver]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSection {
    #[serde(default = "default_time_steps")]
    pub time_steps_per_cycle: usize,
    #[serde(default = "default_max_cycles")]
    pub max_cycles: usize,
    #[serde(default = "default_periodicity")]
    pub periodicity_tolerance: f64,
    #[serde(default = "default_force_tolerance")]
    pub force_tolerance: f64,
    #[serde(default = "default_eccentricity_limit")]
    pub eccentricity_limit: f64,
    #[serde(default = "default_time_scheme")]
    pub time_scheme: String,
    #[serde(default = "default_mobility_model")]
    pub mobility_model: String,
    #[serde(default)]
    pub initial_eccentricity: [f64; 2],
    #[serde(default = "default_rigorous_film")]
    pub rigorous_film: String,
    #[serde(default = "default_step_error_tolerance")]
    pub step_error_tolerance: f64,
    #[serde(default = "default_cycle_extrapolation")]
    pub cycle_extrapolation: bool,
}

impl Default for SolverSection {
    fn default() -> Self {
        Self {
            time_steps_per_cycle: default_time_steps(),
            max_cycles: default_max_cycles(),
            periodicity_tolerance: default_periodicity(),
            force_tolerance: default_force_tolerance(),
            eccentricity_limit: default_eccentricity_limit(),
            time_scheme: default_time_scheme(),
            mobility_model: default_mobility_model(),
            initial_eccentricity: [0.0, 0.0],
            rigorous_film: default_rigorous_film(),
            step_error_tolerance: default_step_error_tolerance(),
            cycle_extrapolation: default_cycle_extrapolation(),
        }
    }
}

/// `[output]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSection {
    #[serde(default = "default_samples")]
    pub samples_per_cycle: usize,
    #[serde(default = "default_snapshots")]
    pub field_snapshots: usize,
    #[serde(default = "default_true")]
    pub plots: bool,
}

impl Default for OutputSection {
    fn default() -> Self {
        Self {
            samples_per_cycle: default_samples(),
            field_snapshots: default_snapshots(),
            plots: true,
        }
    }
}

/// `[methods]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MethodsSection {
    #[serde(default = "default_true")]
    pub mobility: bool,
    #[serde(default = "default_true")]
    pub rigorous: bool,
    #[serde(default)]
    pub closed_form: bool,
}

impl Default for MethodsSection {
    fn default() -> Self {
        Self {
            mobility: true,
            rigorous: true,
            closed_form: false,
        }
    }
}

/// Mineral oil, ~1.5 GPa (docs/conventions.md §2: order 1–2 GPa).
fn default_bulk_modulus() -> f64 {
    1.5e9
}
/// Yu & Sawicki's cut-off groove film fraction (\[YuSawicki2002\], Fig. 4: φ = 0.01).
fn default_starved_film_fraction() -> f64 {
    0.01
}
fn default_interpolation() -> String {
    "linear".into()
}
/// 1° of crank angle per step at a 360° cycle.
fn default_time_steps() -> usize {
    360
}
fn default_max_cycles() -> usize {
    20
}
/// The library's default (the validation's): local error per step 1e-3 in ε.
fn default_step_error_tolerance() -> f64 {
    jbearing_solvers::inverse::InverseParams::default().step_error_tolerance
}
fn default_cycle_extrapolation() -> bool {
    jbearing_solvers::inverse::InverseParams::default().cycle_extrapolation
}
fn default_periodicity() -> f64 {
    1e-4
}
fn default_force_tolerance() -> f64 {
    1e-6
}
fn default_eccentricity_limit() -> f64 {
    0.98
}
fn default_mobility_model() -> String {
    "booker".into()
}
fn default_rigorous_film() -> String {
    "reynolds".into()
}
fn default_samples() -> usize {
    360
}
fn default_snapshots() -> usize {
    36
}
fn default_time_scheme() -> String {
    jbearing_solvers::time_scheme::TimeScheme::default()
        .name()
        .to_string()
}

fn default_true() -> bool {
    true
}

#[cfg(test)]
mod tests {
    use crate::case::{Case, test_case_text};
    use std::path::Path;

    /// The unit-test case (L/D = 0.333) with its length scaled to `length_m` and `grid` appended.
    fn case_with(length_m: f64, grid: &str) -> Case {
        let text = test_case_text(
            "grid",
            "crank_angle_deg = [0.0, 180.0]\nx_n = [-1000.0, -500.0]\ny_n = [0.0, 0.0]",
            grid,
        )
        .replace("length_m = 0.018288", &format!("length_m = {length_m}"))
        .replace("axial_width_m = 0.00381", "axial_width_m = 0.003");
        Case::from_text(&text, Path::new("grid.toml")).unwrap()
    }

    /// Keys left out take the library's grid of the bearing's L/D (the validated default:
    /// 120 × 31, 160 × 23 below L/D 1/4); keys given win, one at a time.
    #[test]
    fn default_grid_follows_the_length_ratio() {
        let d = 2.0 * 0.02743;
        let long = case_with(0.018288, "");
        assert_eq!((long.n_theta, long.n_z), (120, 31));
        let short = case_with(0.2 * d, "");
        assert_eq!((short.n_theta, short.n_z), (160, 23));
        let given = case_with(0.2 * d, "\n[grid]\nn_z = 11\n");
        assert_eq!((given.n_theta, given.n_z), (160, 11));
        let given = case_with(0.5 * d, "\n[grid]\nn_theta = 90\n");
        assert_eq!((given.n_theta, given.n_z), (90, 31));
    }
}
