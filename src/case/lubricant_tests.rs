//! `[lubricant]`: named oils, the heat balance and the Barus coefficient resolve to what the
//! solvers take, and the combinations that make no sense are refused with the key named.

use super::{Case, CaseError};
use jbearing_solvers::viscosity::IsoViscosityGrade;
use std::path::Path;

/// The unit-test case with its `[lubricant]` body replaced by `lubricant`.
fn case_with(lubricant: &str) -> Result<Case, CaseError> {
    let text = super::test_case_text(
        "lubricant",
        "crank_angle_deg = [0.0, 180.0]\nx_n = [-1000.0, -500.0]\ny_n = [0.0, 0.0]",
        "",
    )
    .replace("[lubricant]\nviscosity_pa_s = 0.02\n", lubricant);
    Case::from_text(&text, Path::new("lubricant.toml"))
}

#[test]
fn named_oil_with_a_heat_balance() {
    let case = case_with(
        "[lubricant]\noil = \"iso vg 68\"\n\n[lubricant.heat_balance]\nsupply_temperature_c = 50.0\n\
         heat_to_housing_and_shaft = 0.25\n",
    )
    .unwrap();
    let vg68 = IsoViscosityGrade::Vg68.vogel();
    let h = case.heat_balance.expect("heat balance");
    assert_eq!(h.vogel, vg68);
    assert_eq!(h.params.supply_temperature, 50.0);
    assert_eq!(h.params.heat_to_structure, 0.25);
    assert_eq!(case.oil.as_deref(), Some("ISO VG 68"));
    // Until the balance moves it: the supply temperature's viscosity, no field.
    assert_eq!(case.viscosity, vg68.viscosity(50.0));
    assert!(case.viscosity_model.is_none());
    // One trial of the balance: μ(T), and a Barus model only when α > 0.
    let trial = case.at_film_temperature(75.0);
    assert_eq!(trial.viscosity, vg68.viscosity(75.0));
    assert!(trial.viscosity_model.is_none());
}

#[test]
fn barus_coefficient_reaches_the_film_model() {
    let case = case_with(
        "[lubricant]\noil = \"ISO VG 680\"\npressure_viscosity_coefficient_per_pa = 1e-8\n\n\
         [lubricant.temperature]\nmean_c = 60.0\n",
    )
    .unwrap();
    let m = case.viscosity_model.expect("model");
    assert_eq!(m.pressure_coefficient, 1e-8);
    let hb = case_with(
        "[lubricant]\noil = \"ISO VG 680\"\npressure_viscosity_coefficient_per_pa = 2e-8\n\n\
         [lubricant.heat_balance]\nsupply_temperature_c = 40.0\n",
    )
    .unwrap();
    let trial = hb.at_film_temperature(70.0);
    let m = trial.viscosity_model.expect("a Barus model at T_eff");
    assert_eq!(m.pressure_coefficient, 2e-8);
    assert_eq!(m.vogel.viscosity(70.0), trial.viscosity);
}

#[test]
fn nonsense_combinations_name_their_key() {
    let refused = |lubricant: &str, key: &str| {
        let err = case_with(lubricant).unwrap_err().to_string();
        assert!(err.contains(key), "{key}: {err}");
    };
    refused(
        "[lubricant]\nviscosity_pa_s = 0.02\npressure_viscosity_coefficient_per_pa = 1e-8\n",
        "lubricant.pressure_viscosity_coefficient_per_pa",
    );
    refused(
        "[lubricant]\noil = \"ISO VG 68\"\npressure_viscosity_coefficient_per_pa = -1e-8\n\n\
         [lubricant.temperature]\nmean_c = 60.0\n",
        "lubricant.pressure_viscosity_coefficient_per_pa",
    );
    refused(
        "[lubricant]\nviscosity_pa_s = 0.02\n\n[lubricant.heat_balance]\nsupply_temperature_c = 50.0\n",
        "lubricant.heat_balance",
    );
    refused(
        "[lubricant]\noil = \"ISO VG 68\"\n\n[lubricant.vogel]\na_pa_s = 1e-4\nb_c = 900.0\nc_c = -70.0\n\n\
         [lubricant.temperature]\nmean_c = 60.0\n",
        "lubricant.oil",
    );
    refused(
        "[lubricant]\noil = \"ISO VG 68\"\n\n[lubricant.heat_balance]\nsupply_temperature_c = 50.0\n\
         max_iterations = 1\n",
        "lubricant.heat_balance.max_iterations",
    );
}
