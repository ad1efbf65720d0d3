//! The closed-form static-equilibrium table of a case: one row per closed-form film model
//! (`jbearing_solvers::closed_form`), and for a steady case the finite-difference Reynolds
//! answer beside them. Written to `CASE.h5` as the group `closed_form/` along a `model`
//! dimension (see [`super::hdf5`]) and printed by `jbearing run` and `jbearing closed-form`.
//!
//! ```text
//! ClosedFormTable
//! ├── load [N], relative_speed [rad/s], load_basis   what every row balances
//! └── rows: [ClosedFormRow]                          one per model
//!       model, status ("ok" or the solver's error), ε, φ, γ, h_min, F, |F + W|, S
//! ```
//!
//! A value a row does not have (a model that failed, a force the FD row does not report) is NaN,
//! written as the `_FillValue`.

/// One row: the static equilibrium of one model.
#[derive(Debug, Clone, PartialEq)]
pub struct ClosedFormRow {
    /// Model name (`short_gumbel`, …, or `fd_reynolds` for the finite-difference answer).
    pub model: String,
    /// `"ok"`, or why the model has no equilibrium (e.g. film collapse).
    pub status: String,
    /// ε \[1\].
    pub eccentricity_ratio: f64,
    /// Attitude angle φ: from the load line to the line of centres, positive in the direction of
    /// rotation \[rad\].
    pub attitude_angle: f64,
    /// γ: angle of the line of centres from +x (bearing frame) \[rad\].
    pub line_of_centres_angle: f64,
    /// h_min = c (1 − ε) \[m\].
    pub min_film_thickness: f64,
    /// Film force on the journal at the equilibrium, bearing frame \[N\].
    pub film_force: [f64; 2],
    /// Force balance |F + W| \[N\].
    pub force_residual: f64,
    /// Sommerfeld number S = μ N L D / |W| (R/c)² \[1\].
    pub sommerfeld_number: f64,
}

/// The table of a case.
#[derive(Debug, Clone, PartialEq)]
pub struct ClosedFormTable {
    /// The load W every row balances (force on the journal, bearing frame) \[N\].
    pub load: [f64; 2],
    /// Relative speed ω = ω_j − ω_b \[rad/s\].
    pub relative_speed: f64,
    /// Where the load comes from ("constant load of a steady case", "cycle-mean load").
    pub load_basis: String,
    /// One row per model.
    pub rows: Vec<ClosedFormRow>,
}

impl ClosedFormRow {
    /// The numeric columns: (variable name, value, units, long name).
    pub fn columns(&self) -> [(&'static str, f64, &'static str, &'static str); 8] {
        [
            (
                "eccentricity_ratio",
                self.eccentricity_ratio,
                "1",
                "eccentricity ratio at the static equilibrium",
            ),
            (
                "attitude_angle",
                self.attitude_angle,
                "rad",
                "attitude angle from the load line to the line of centres, positive in the \
                 direction of rotation",
            ),
            (
                "line_of_centres_angle",
                self.line_of_centres_angle,
                "rad",
                "angle of the line of centres from +x towards +y (bearing frame)",
            ),
            (
                "min_film_thickness",
                self.min_film_thickness,
                "m",
                "minimum film thickness",
            ),
            (
                "film_force_x",
                self.film_force[0],
                "N",
                "film force on the journal, x component",
            ),
            (
                "film_force_y",
                self.film_force[1],
                "N",
                "film force on the journal, y component",
            ),
            (
                "force_residual",
                self.force_residual,
                "N",
                "force balance |F + W| at the equilibrium",
            ),
            (
                "sommerfeld_number",
                self.sommerfeld_number,
                "1",
                "Sommerfeld number mu N L D / W (R/c)^2",
            ),
        ]
    }
}

impl ClosedFormTable {
    /// Checks what the writers rely on: model names usable as labels and unique, no infinite
    /// value (NaN marks a missing value), finite load and speed.
    pub fn validate(&self) -> Result<(), String> {
        for (what, v) in [
            ("load_x", self.load[0]),
            ("load_y", self.load[1]),
            ("relative_speed", self.relative_speed),
        ] {
            if !v.is_finite() {
                return Err(format!("closed_form {what} = {v} is not finite"));
            }
        }
        let mut seen = std::collections::HashSet::new();
        for r in &self.rows {
            if r.model.is_empty() || !seen.insert(r.model.as_str()) {
                return Err(format!("closed_form model '{}' empty or repeated", r.model));
            }
            for (name, v, _, _) in r.columns() {
                if v.is_infinite() {
                    return Err(format!("closed_form {} {name} = {v} is infinite", r.model));
                }
            }
        }
        Ok(())
    }
}
