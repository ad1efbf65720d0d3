//! `[elastic]`'s gap tolerance: left out, the steady solve and the dynamic film each run their
//! validated default; a dynamic one looser than the Newton needs is warned about.

use super::Case;
use jbearing_solvers::elastic::ElasticParams;
use std::path::Path;

fn repository_case(name: &str) -> Case {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("cases")
        .join(name);
    Case::from_file(&path).unwrap()
}

fn gap_warned(case: &Case) -> bool {
    case.warnings
        .iter()
        .any(|w| w.key == "elastic.gap_tolerance")
}

/// The compressor rod's elastic case leaves the key out: its dynamic film runs 1e-8 c (what
/// its validated row ran, docs/validation.md), the steady solve keeps 1e-5 c, no warning. The
/// gap 1e-4 c case sets both and is warned about; JB1 (steady, no rigorous method) leaves it
/// out too and runs the steady 1e-5 c.
#[test]
fn dynamic_gap_tolerance_defaults_to_the_validated_value() {
    let rod = repository_case("compressor_rod_elastic.toml");
    let e = rod.elastic.as_ref().unwrap();
    assert_eq!(e.dynamic_gap_tolerance, 1e-8);
    assert_eq!(
        e.dynamic_gap_tolerance,
        ElasticParams::dynamic_gap_tolerance_for(rod.solver.force_tolerance)
    );
    assert_eq!(e.gap_tolerance, ElasticParams::steel(1.0).gap_tolerance);
    assert!(!gap_warned(&rod));
    let loose = repository_case("compressor_rod_elastic_gap1e-4.toml");
    let e = loose.elastic.as_ref().unwrap();
    assert_eq!((e.gap_tolerance, e.dynamic_gap_tolerance), (1e-4, 1e-4));
    assert!(gap_warned(&loose));
    let jb1 = repository_case("benasciutti_jb1_elastic.toml");
    assert_eq!(jb1.elastic.as_ref().unwrap().gap_tolerance, 1e-5);
    assert!(!gap_warned(&jb1));
}
