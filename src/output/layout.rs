//! The parts of the `CASE.h5` layout that the report does not carry itself: the coordinate
//! variables, the geometry scalars, and the long names and descriptions of the groups. One
//! table, read by the HDF5 writer ([`super::Hdf5Writer`]) and exported to the Python package
//! (`jbearing._jbearing.layout()`), so the file and the xarray tree spell them alike.

/// A variable's name, units (CF/UDUNITS; empty for dimensionless or text) and long name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Variable {
    /// Dataset (and, for a coordinate, dimension) name.
    pub name: &'static str,
    /// `units` attribute.
    pub units: &'static str,
    /// `long_name` attribute.
    pub long_name: &'static str,
}

/// Crank angle of a method's samples (its dimension).
pub const CRANK_ANGLE: Variable = Variable {
    name: "crank_angle",
    units: "degree",
    long_name: "crank angle",
};
/// Time of a method's samples, on `crank_angle`.
pub const TIME: Variable = Variable {
    name: "time",
    units: "s",
    long_name: "time within the cycle",
};
/// Crank angle of the stored field instants (the `fields` group's own dimension: a child group
/// may not reuse its parent's dimension with another length).
pub const FIELD_CRANK_ANGLE: Variable = Variable {
    name: "field_crank_angle",
    units: "degree",
    long_name: "crank angle of the stored instant",
};
/// Time of the stored field instants, on `field_crank_angle`.
pub const FIELD_TIME: Variable = Variable {
    name: "field_time",
    units: "s",
    long_name: "time within the cycle of the stored instant",
};
/// Circumferential coordinate of the film fields.
pub const THETA: Variable = Variable {
    name: "theta",
    units: "rad",
    long_name: "circumferential angle from +x towards +y (bearing frame)",
};
/// Axial coordinate of the film fields.
pub const Z: Variable = Variable {
    name: "z",
    units: "m",
    long_name: "axial position from the bearing mid-plane",
};
/// Geometry scalars in the root group.
pub const RADIUS: Variable = Variable {
    name: "radius",
    units: "m",
    long_name: "bearing radius",
};
/// Bearing length.
pub const LENGTH: Variable = Variable {
    name: "length",
    units: "m",
    long_name: "bearing length",
};
/// Radial clearance.
pub const RADIAL_CLEARANCE: Variable = Variable {
    name: "radial_clearance",
    units: "m",
    long_name: "radial clearance",
};
/// The summary group's method coordinate (not `method`: xarray's `.sel(method=…)` would take it
/// for its own keyword).
pub const SOLUTION_METHOD: Variable = Variable {
    name: "solution_method",
    units: "",
    long_name: "solution method",
};
/// The closed-form group's model coordinate.
pub const MODEL: Variable = Variable {
    name: "model",
    units: "",
    long_name: "film model",
};
/// The closed-form group's status of each model.
pub const STATUS: Variable = Variable {
    name: "status",
    units: "",
    long_name: "ok, or why the model has no equilibrium",
};
/// The input files' path coordinate.
pub const INPUT_FILE: Variable = Variable {
    name: "file",
    units: "",
    long_name: "path as referenced by the case file",
};
/// The input files' contents.
pub const INPUT_TEXT: Variable = Variable {
    name: "text",
    units: "",
    long_name: "file contents",
};

/// The root group's `Conventions`.
pub const CONVENTIONS: &str = "CF-1.10";
/// `description` of the `parameters` group.
pub const PARAMETERS_DESCRIPTION: &str = "resolved case parameters (defaults filled in)";
/// `description` of a method's `fields` group.
pub const FIELDS_DESCRIPTION: &str = "film fields on the (theta, z) grid at the stored instants \
     of the final cycle; theta is periodic (theta = 2 pi is theta = 0, not repeated)";
/// `description` of the `input_files` group.
pub const INPUT_FILES_DESCRIPTION: &str = "input files the case refers to, verbatim";
/// `description` of the `summary` group.
pub const SUMMARY_DESCRIPTION: &str =
    "cycle figures per method; mobility deviation = (mobility - rigorous) / |rigorous|";
/// `description` of the `closed_form` group.
pub const CLOSED_FORM_DESCRIPTION: &str = "static equilibrium of the closed-form film models \
     (jbearing_solvers::closed_form) under a constant load; fd_reynolds: the finite-difference \
     Reynolds (rigorous) answer of a steady case";

/// Every variable of the table, keyed by its name (what the Python package reads).
pub const VARIABLES: [Variable; 14] = [
    CRANK_ANGLE,
    TIME,
    FIELD_CRANK_ANGLE,
    FIELD_TIME,
    THETA,
    Z,
    RADIUS,
    LENGTH,
    RADIAL_CLEARANCE,
    SOLUTION_METHOD,
    MODEL,
    STATUS,
    INPUT_FILE,
    INPUT_TEXT,
];

/// Every text of the table, keyed as the Python package reads them.
pub const TEXTS: [(&str, &str); 6] = [
    ("conventions", CONVENTIONS),
    ("parameters_description", PARAMETERS_DESCRIPTION),
    ("fields_description", FIELDS_DESCRIPTION),
    ("input_files_description", INPUT_FILES_DESCRIPTION),
    ("summary_description", SUMMARY_DESCRIPTION),
    ("closed_form_description", CLOSED_FORM_DESCRIPTION),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique() {
        let mut names: Vec<_> = VARIABLES.iter().map(|v| v.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), VARIABLES.len());
    }
}
