//! HDF5 output of one case: a netCDF-4-compatible file that xarray opens with named dimensions
//! and coordinates, with a VTKHDF surface beside it for pyvista / ParaView.
//!
//! Layout of `CASE.h5` (dimension names in parentheses; every variable has `units` and
//! `long_name` attributes):
//!
//! ```text
//! /                      attrs: Conventions = "CF-1.10", title, source, history, case_name,
//! │                             case_text (the case file as given), case_path (absolute),
//! │                             jbearing_version, git_commit, wall_time_s, started_utc,
//! │                             warning_count, warnings[], warning_kinds[] (when any)
//! │  radius, length, radial_clearance          scalars [m]
//! ├── parameters/        one scalar variable per resolved parameter (numbers with units;
//! │                      text as strings; flags as 0/1 bytes)
//! ├── rigorous/          attrs: method, description, solver information
//! │   │  crank_angle(crank_angle) [degree]      coordinate (dimension scale): 0, Δ, …, cycle − Δ,
//! │   │                                       the same exact values for both methods
//! │   │  time(crank_angle) [s]                  auxiliary coordinate (time within the cycle)
//! │   │  <series>(crank_angle)                  load_x, feed_pressure, min_film_thickness, …
//! │   └── fields/
//! │         field_crank_angle(field_crank_angle) the stored instants (own dimension: a DataTree
//! │         field_time(field_crank_angle) [s]    child may not reuse its parent's dimension)
//! │         theta(theta) [rad], z(z) [m]        the grid
//! │         <field>(field_crank_angle, theta, z) pressure, film_thickness, film_content
//! ├── mobility/          as rigorous/, without fields/
//! ├── input_files/       file(file): paths the case refers to; text(file): their contents
//! ├── summary/
//! │      solution_method(solution_method)       "rigorous", "mobility"
//! │      <row>(solution_method)                 NaN (= _FillValue) where a method lacks it
//! ├── closed_form/       (when the case asks for it) attrs: load_x, load_y [N], relative_speed
//! │      model(model)                           "short_gumbel", "long_sommerfeld", …, "fd_reynolds"
//! │      status(model)                          "ok" or why the model has no equilibrium
//! │      eccentricity_ratio(model) [1], attitude_angle(model) [rad], line_of_centres_angle,
//! │      min_film_thickness [m], film_force_x/y [N], force_residual [N], sommerfeld_number [1]
//! ├── elastic/           (a case with `[elastic]`) the deformable bearing along the film surface:
//! │      angle(angle) [rad], surface_pressure, gap_change, film_thickness, bore_* and journal_*
//! │      stresses (σ_r, σ_θ, σ_z, von Mises) [Pa]; scalars (see `super::elastic`)
//! └── VTKHDF/            film fields on the cylindrical surface (see `vtkhdf`), or for a case
//!                        with `[elastic]` the shaft and housing meshes with displacement and
//!                        stress (`vtkhdf::write_bodies`)
//! ```
//!
//! Dimensions are netCDF-4 style: each coordinate variable is an HDF5 dimension scale
//! (`CLASS = "DIMENSION_SCALE"`, `NAME`, `REFERENCE_LIST`, made by the HDF5 high-level library's
//! `H5DSset_scale`, the call netCDF-C itself makes) and each data variable has the scales
//! attached per axis (`DIMENSION_LIST`, by `H5DSattach_scale`). Scales also carry
//! `_Netcdf4Dimid`, numbered in creation order through the file as netCDF-C does. That is what
//! h5netcdf (and so `xarray.open_dataset(path, engine="h5netcdf", group="rigorous")`) reads to
//! name the axes; without it the variables would have anonymous "phony" dimensions.
//!
//! The whole file is written to a temporary file in the output directory and renamed into place
//! when complete (see [`super::write_atomically`]).

use std::ffi::{CString, c_char, c_uint};
use std::path::{Path, PathBuf};

use hdf5_metno as h5;
use hdf5_metno::types::VarLenUnicode;
use hdf5_metno_sys::h5::herr_t;
use hdf5_metno_sys::h5i::hid_t;

use super::layout;
use super::{
    CaseReport, ClosedFormTable, ElasticReport, FieldSnapshots, Method, MethodResult, OutputError,
    OutputWriter, ParameterValue, vtkhdf, write_atomically,
};

// The dimension-scale API of the HDF5 high-level library (libhdf5_hl, linked through the "hl"
// feature of hdf5-metno-sys, which has no bindings for it).
unsafe extern "C" {
    fn H5DSset_scale(dsid: hid_t, dimname: *const c_char) -> herr_t;
    fn H5DSattach_scale(did: hid_t, dsid: hid_t, idx: c_uint) -> herr_t;
}

/// Writes `CASE.h5` (see the module documentation for the layout).
#[derive(Debug, Clone)]
pub struct Hdf5Writer {
    /// Also write the `VTKHDF` surface group (default: true).
    pub vtkhdf_surface: bool,
}

impl Default for Hdf5Writer {
    fn default() -> Self {
        Self::new()
    }
}

impl Hdf5Writer {
    /// A writer that includes the VTKHDF surface.
    pub fn new() -> Self {
        Self {
            vtkhdf_surface: true,
        }
    }

    /// Path of the file written for `report` in `dir`.
    pub fn file_path(report: &CaseReport, dir: &Path) -> PathBuf {
        dir.join(format!("{}.h5", report.case_name))
    }

    /// Validates `report` and writes it to `path` atomically.
    pub fn write_file(&self, report: &CaseReport, path: &Path) -> Result<(), OutputError> {
        report.validate()?;
        write_atomically(path, |tmp| {
            let file = h5::File::create(tmp).map_err(|source| OutputError::Hdf5 {
                path: path.to_path_buf(),
                context: "creating the file".into(),
                source,
            })?;
            let mut w = FileWriter {
                path: path.to_path_buf(),
                next_dimid: 0,
            };
            w.write_report(&file, report, self.vtkhdf_surface)?;
            file.close().map_err(w.err("closing the file"))
        })
    }
}

impl OutputWriter for Hdf5Writer {
    fn name(&self) -> &'static str {
        "hdf5"
    }

    fn write(&self, report: &CaseReport, dir: &Path) -> Result<Vec<PathBuf>, OutputError> {
        let path = Self::file_path(report, dir);
        self.write_file(report, &path)?;
        Ok(vec![path])
    }
}

/// State of one file being written: its final path for messages and the netCDF dimension ids.
/// Also the writer of `jbearing merge` ([`crate::merge`]).
pub(crate) struct FileWriter {
    path: PathBuf,
    next_dimid: i32,
}

type Res<T> = Result<T, OutputError>;

impl FileWriter {
    /// A writer for a file whose final path is `path` (used in messages).
    pub(crate) fn new(path: &Path) -> Self {
        Self {
            path: path.to_path_buf(),
            next_dimid: 0,
        }
    }

    /// A string coordinate variable that is its own dimension (`solution_method`, `case`).
    pub(crate) fn string_coordinate(
        &mut self,
        g: &h5::Group,
        name: &str,
        labels: &[String],
        long_name: &str,
    ) -> Res<h5::Dataset> {
        let ds = self.strings(g, name, labels, long_name)?;
        self.make_scale(&ds, name)?;
        Ok(ds)
    }

    /// A string data variable along one dimension.
    pub(crate) fn string_variable(
        &mut self,
        g: &h5::Group,
        name: &str,
        values: &[String],
        dim: &h5::Dataset,
        long_name: &str,
    ) -> Res<h5::Dataset> {
        let ds = self.strings(g, name, values, long_name)?;
        self.attach(&ds, &[dim], name)?;
        Ok(ds)
    }

    /// A 1-D dataset of UTF-8 strings with its long name.
    fn strings(
        &mut self,
        g: &h5::Group,
        name: &str,
        values: &[String],
        long_name: &str,
    ) -> Res<h5::Dataset> {
        let v: Vec<VarLenUnicode> = values.iter().map(|l| vlen(l)).collect();
        let ds = g
            .new_dataset_builder()
            .with_data(&v[..])
            .create(name)
            .map_err(self.err(format!("variable {name}")))?;
        self.str_attr(&ds, "long_name", long_name)?;
        Ok(ds)
    }

    /// A 2-D f64 data variable along two dimension scales, NaN as its fill value.
    pub(crate) fn variable_2d(
        &mut self,
        g: &h5::Group,
        name: &str,
        values: &ndarray::Array2<f64>,
        dims: [&h5::Dataset; 2],
        units: &str,
        long_name: &str,
    ) -> Res<h5::Dataset> {
        let ds = g
            .new_dataset_builder()
            .with_data(values)
            .create(name)
            .map_err(self.err(format!("variable {name}")))?;
        self.attach(&ds, &dims, name)?;
        self.str_attr(&ds, "units", units)?;
        self.str_attr(&ds, "long_name", long_name)?;
        self.f64_attr(&ds, "_FillValue", f64::NAN)?;
        Ok(ds)
    }
    pub(crate) fn err<C: Into<String>>(
        &self,
        context: C,
    ) -> impl FnOnce(h5::Error) -> OutputError + use<C> {
        let path = self.path.clone();
        let context = context.into();
        move |source| OutputError::Hdf5 {
            path,
            context,
            source,
        }
    }

    /// The whole file: global attributes, geometry, parameters, one group per method, the
    /// summary, closed forms, input files, the deformable bearing and the VTKHDF dataset.
    fn write_report(&mut self, file: &h5::File, r: &CaseReport, surface: bool) -> Res<()> {
        self.write_global_attributes(file, r)?;
        let g = r.geometry;
        for (v, value) in [
            (layout::RADIUS, g.radius),
            (layout::LENGTH, g.length),
            (layout::RADIAL_CLEARANCE, g.radial_clearance),
        ] {
            self.scalar(file, v.name, value, v.units, v.long_name)?;
        }

        self.write_parameters(file, r)?;
        for m in &r.methods {
            self.write_method(file, m)?;
        }
        self.write_summary(file, r)?;
        if let Some(t) = &r.closed_form {
            self.write_closed_form(file, t)?;
        }
        if !r.input_files.is_empty() {
            self.write_input_files(file, r)?;
        }

        if let Some(e) = &r.elastic {
            self.write_elastic(file, e)?;
        }

        if surface {
            self.write_vtkhdf(file, r)?;
        }
        Ok(())
    }

    /// The root's attributes: CF conventions, provenance of the run, the methods and warnings.
    fn write_global_attributes(&mut self, file: &h5::File, r: &CaseReport) -> Res<()> {
        let run = &r.run;
        self.str_attr(
            file,
            "title",
            &format!("jbearing results for case '{}'", r.case_name),
        )?;
        // CF-1.10 (https://cfconventions.org): the global attributes; every variable has units
        // and long_name. No standard_name: the CF table has none for bearing quantities, and
        // the time coordinates are times within a periodic cycle without a reference date
        // (a CF time coordinate needs "s since <date>", which xarray would decode to dates).
        self.str_attr(file, "Conventions", layout::CONVENTIONS)?;
        self.str_attr(
            file,
            "source",
            &format!(
                "jbearing {} (commit {})",
                run.jbearing_version, run.git_commit
            ),
        )?;
        self.str_attr(
            file,
            "history",
            &format!("{} jbearing run of case '{}'", run.started_utc, r.case_name),
        )?;
        self.str_attr(file, "case_name", &r.case_name)?;
        self.str_attr(file, "case_text", &r.case_text)?;
        let case_path = r
            .case_path
            .as_ref()
            .map(|p| p.display().to_string())
            .unwrap_or_default();
        self.str_attr(file, "case_path", &case_path)?;
        self.str_attr(file, "jbearing_version", &run.jbearing_version)?;
        self.str_attr(file, "git_commit", &run.git_commit)?;
        self.f64_attr(file, "wall_time_s", run.wall_time)?;
        self.str_attr(file, "started_utc", &run.started_utc)?;
        self.str_attr(
            file,
            "methods",
            &r.methods
                .iter()
                .map(|m| m.method.as_str())
                .collect::<Vec<_>>()
                .join(" "),
        )?;

        file.new_attr::<i64>()
            .shape(())
            .create("warning_count")
            .and_then(|a| a.write_scalar(&(r.warnings.len() as i64)))
            .map_err(self.err("attribute warning_count"))?;
        if !r.warnings.is_empty() {
            let messages: Vec<VarLenUnicode> =
                r.warnings.iter().map(|w| vlen(&w.message)).collect();
            let kinds: Vec<VarLenUnicode> = r.warnings.iter().map(|w| vlen(&w.kind)).collect();
            for (name, values) in [("warnings", messages), ("warning_kinds", kinds)] {
                file.new_attr::<VarLenUnicode>()
                    .shape(values.len())
                    .create(name)
                    .and_then(|a| a.write(&values))
                    .map_err(self.err(format!("attribute {name}")))?;
            }
        }
        Ok(())
    }

    /// The `parameters/` group: every case parameter as a scalar with its units and long name
    /// (flags as 0/1 with `flag_values`).
    fn write_parameters(&mut self, file: &h5::File, r: &CaseReport) -> Res<()> {
        let params = file
            .create_group("parameters")
            .map_err(self.err("group parameters"))?;
        self.str_attr(&params, "description", layout::PARAMETERS_DESCRIPTION)?;
        for p in &r.parameters {
            let ctx = format!("parameter {}", p.key);
            let ds = match &p.value {
                ParameterValue::Number(v) => params
                    .new_dataset::<f64>()
                    .shape(())
                    .create(p.key.as_str())
                    .and_then(|d| d.write_scalar(v).map(|_| d)),
                ParameterValue::Integer(v) => params
                    .new_dataset::<i64>()
                    .shape(())
                    .create(p.key.as_str())
                    .and_then(|d| d.write_scalar(v).map(|_| d)),
                ParameterValue::Flag(v) => params
                    .new_dataset::<i8>()
                    .shape(())
                    .create(p.key.as_str())
                    .and_then(|d| d.write_scalar(&i8::from(*v)).map(|_| d)),
                ParameterValue::Text(v) => {
                    let s = vlen(v);
                    params
                        .new_dataset::<VarLenUnicode>()
                        .shape(())
                        .create(p.key.as_str())
                        .and_then(|d| d.write_scalar(&s).map(|_| d))
                }
            }
            .map_err(self.err(ctx))?;
            if !p.units.is_empty() {
                self.str_attr(&ds, "units", &p.units)?;
            }
            self.str_attr(&ds, "long_name", &p.long_name)?;
            if matches!(p.value, ParameterValue::Flag(_)) {
                ds.new_attr::<i8>()
                    .shape(2)
                    .create("flag_values")
                    .and_then(|a| a.write(&[0i8, 1]))
                    .map_err(self.err(format!("{} flag_values", p.key)))?;
                self.str_attr(&ds, "flag_meanings", "false true")?;
            }
        }
        Ok(())
    }

    /// One VTK dataset per file (/VTKHDF): the structure of a deformable bearing, else the film
    /// surface of the first method with fields.
    fn write_vtkhdf(&mut self, file: &h5::File, r: &CaseReport) -> Res<()> {
        if let Some(e) = &r.elastic {
            vtkhdf::write_bodies(file, &e.bodies).map_err(self.err("VTKHDF shaft and housing"))?;
        } else if let Some((method, fields)) = r
            .methods
            .iter()
            .find_map(|m| m.fields.as_ref().map(|f| (m.method, f)))
        {
            vtkhdf::write_surface(file, &r.geometry, method, fields)
                .map_err(self.err("VTKHDF surface"))?;
        }
        Ok(())
    }

    fn write_method(&mut self, file: &h5::File, m: &MethodResult) -> Res<()> {
        let name = m.method.as_str();
        let g = file
            .create_group(name)
            .map_err(self.err(format!("group {name}")))?;
        self.str_attr(&g, "method", name)?;
        self.str_attr(&g, "description", m.method.description())?;
        for (k, v) in &m.solver_info {
            let ctx = format!("{name} attribute {k}");
            match v {
                ParameterValue::Number(x) => self.f64_attr(&g, k, *x)?,
                ParameterValue::Integer(x) => g
                    .new_attr::<i64>()
                    .shape(())
                    .create(k.as_str())
                    .and_then(|a| a.write_scalar(x))
                    .map_err(self.err(ctx))?,
                ParameterValue::Flag(x) => g
                    .new_attr::<i8>()
                    .shape(())
                    .create(k.as_str())
                    .and_then(|a| a.write_scalar(&i8::from(*x)))
                    .map_err(self.err(ctx))?,
                ParameterValue::Text(x) => self.str_attr(&g, k, x)?,
            }
        }
        // The dimension is the crank angle (exact grid values shared by both methods, so that
        // `.sel(crank_angle=90)` and `rigorous - mobility` work); time is an auxiliary coordinate.
        let crank = self.coordinate_of(&g, layout::CRANK_ANGLE, &m.crank_angle)?;
        self.auxiliary(&g, layout::TIME, &m.time, &crank)?;
        for s in &m.series {
            let ds = self.variable(&g, &s.name, &s.values, &[&crank])?;
            self.str_attr(&ds, "units", &s.units)?;
            self.str_attr(&ds, "long_name", &s.long_name)?;
            self.str_attr(&ds, "coordinates", layout::TIME.name)?;
        }
        if let Some(f) = &m.fields {
            self.write_fields(&g, name, f)?;
        }
        Ok(())
    }

    /// `fields/` under `parent`: `field_crank_angle` (dimension) with `field_time`, `theta`,
    /// `z` and one (instant, θ, z) variable per field; `method` names the group in messages.
    pub(crate) fn write_fields(
        &mut self,
        parent: &h5::Group,
        method: &str,
        f: &FieldSnapshots,
    ) -> Res<()> {
        let g = parent
            .create_group("fields")
            .map_err(self.err(format!("group {method}/fields")))?;
        self.str_attr(&g, "description", layout::FIELDS_DESCRIPTION)?;
        // Its own dimension name: a child group may not reuse its parent's `time` with another
        // length (xarray's DataTree requires every group aligned with its parents).
        let crank = self.coordinate_of(&g, layout::FIELD_CRANK_ANGLE, &f.crank_angle)?;
        self.auxiliary(&g, layout::FIELD_TIME, &f.time, &crank)?;
        let theta = self.coordinate_of(&g, layout::THETA, &f.theta)?;
        let z = self.coordinate_of(&g, layout::Z, &f.z)?;
        let (nt, nth, nz) = (f.time.len(), f.theta.len(), f.z.len());
        for fld in &f.fields {
            let ctx = format!("{method}/fields/{}", fld.name);
            let mut b = g.new_dataset_builder();
            if h5::filters::deflate_available() {
                // One chunk per instant: a reader slicing one time reads one chunk.
                b = b.chunk((1, nth, nz)).shuffle().deflate(4);
            }
            let ds = b
                .with_data(fld.values.view())
                .create(fld.name.as_str())
                .map_err(self.err(ctx))?;
            debug_assert_eq!(ds.shape(), vec![nt, nth, nz]);
            self.attach(&ds, &[&crank, &theta, &z], &fld.name)?;
            self.str_attr(&ds, "units", &fld.units)?;
            self.str_attr(&ds, "long_name", &fld.long_name)?;
            self.str_attr(&ds, "coordinates", layout::FIELD_TIME.name)?;
        }
        self.str_attr(&theta, "axis", "X")?;
        self.str_attr(&z, "axis", "Y")?;
        Ok(())
    }

    fn write_input_files(&mut self, file: &h5::File, r: &CaseReport) -> Res<()> {
        let g = file
            .create_group("input_files")
            .map_err(self.err("group input_files"))?;
        self.str_attr(&g, "description", layout::INPUT_FILES_DESCRIPTION)?;
        let paths: Vec<VarLenUnicode> = r.input_files.iter().map(|f| vlen(&f.path)).collect();
        let texts: Vec<VarLenUnicode> = r.input_files.iter().map(|f| vlen(&f.text)).collect();
        let file_dim = g
            .new_dataset_builder()
            .with_data(&paths[..])
            .create(layout::INPUT_FILE.name)
            .map_err(self.err("input_files/file"))?;
        self.make_scale(&file_dim, layout::INPUT_FILE.name)?;
        self.str_attr(&file_dim, "long_name", layout::INPUT_FILE.long_name)?;
        let text = g
            .new_dataset_builder()
            .with_data(&texts[..])
            .create(layout::INPUT_TEXT.name)
            .map_err(self.err("input_files/text"))?;
        self.attach(&text, &[&file_dim], layout::INPUT_TEXT.name)?;
        self.str_attr(&text, "long_name", layout::INPUT_TEXT.long_name)
    }

    fn write_summary(&mut self, file: &h5::File, r: &CaseReport) -> Res<()> {
        let g = file
            .create_group("summary")
            .map_err(self.err("group summary"))?;
        self.str_attr(&g, "description", layout::SUMMARY_DESCRIPTION)?;
        let labels: Vec<VarLenUnicode> = Method::ALL.iter().map(|m| vlen(m.as_str())).collect();
        let method = g
            .new_dataset_builder()
            .with_data(&labels[..])
            .create(layout::SOLUTION_METHOD.name)
            .map_err(self.err("summary/solution_method"))?;
        self.make_scale(&method, layout::SOLUTION_METHOD.name)?;
        self.str_attr(&method, "long_name", layout::SOLUTION_METHOD.long_name)?;
        for row in &r.summary {
            let values: Vec<f64> = Method::ALL
                .iter()
                .map(|m| row.value(*m).unwrap_or(f64::NAN))
                .collect();
            let ds = self.variable(&g, &row.name, &values, &[&method])?;
            self.str_attr(&ds, "units", &row.units)?;
            self.str_attr(&ds, "long_name", &row.long_name)?;
            self.f64_attr(&ds, "_FillValue", f64::NAN)?;
        }
        Ok(())
    }

    fn write_closed_form(&mut self, file: &h5::File, t: &ClosedFormTable) -> Res<()> {
        let g = file
            .create_group("closed_form")
            .map_err(self.err("group closed_form"))?;
        self.str_attr(&g, "description", layout::CLOSED_FORM_DESCRIPTION)?;
        self.str_attr(&g, "load_basis", &t.load_basis)?;
        self.f64_attr(&g, "load_x", t.load[0])?;
        self.f64_attr(&g, "load_y", t.load[1])?;
        self.f64_attr(&g, "relative_speed", t.relative_speed)?;
        let labels: Vec<VarLenUnicode> = t.rows.iter().map(|r| vlen(&r.model)).collect();
        let model = g
            .new_dataset_builder()
            .with_data(&labels[..])
            .create(layout::MODEL.name)
            .map_err(self.err("closed_form/model"))?;
        self.make_scale(&model, layout::MODEL.name)?;
        self.str_attr(&model, "long_name", layout::MODEL.long_name)?;
        let status: Vec<VarLenUnicode> = t.rows.iter().map(|r| vlen(&r.status)).collect();
        let st = g
            .new_dataset_builder()
            .with_data(&status[..])
            .create(layout::STATUS.name)
            .map_err(self.err("closed_form/status"))?;
        self.attach(&st, &[&model], layout::STATUS.name)?;
        self.str_attr(&st, "long_name", layout::STATUS.long_name)?;
        let Some(first) = t.rows.first() else {
            return Ok(());
        };
        for (k, (name, _, units, long)) in first.columns().into_iter().enumerate() {
            let values: Vec<f64> = t.rows.iter().map(|r| r.columns()[k].1).collect();
            let ds = self.variable(&g, name, &values, &[&model])?;
            self.str_attr(&ds, "units", units)?;
            self.str_attr(&ds, "long_name", long)?;
            self.f64_attr(&ds, "_FillValue", f64::NAN)?;
        }
        Ok(())
    }

    fn write_elastic(&mut self, file: &h5::File, e: &ElasticReport) -> Res<()> {
        let g = file
            .create_group("elastic")
            .map_err(self.err("group elastic"))?;
        self.str_attr(&g, "description", &e.description)?;
        for p in &e.scalars {
            let v = match p.value {
                ParameterValue::Number(v) => v,
                ParameterValue::Integer(v) => v as f64,
                _ => continue,
            };
            self.scalar(&g, &p.key, v, &p.units, &p.long_name)?;
        }
        let angle = self.coordinate(
            &g,
            "angle",
            &e.angle,
            "rad",
            "angle of the film-surface node from +x towards +y (bearing frame)",
        )?;
        for s in &e.series {
            let ds = self.variable(&g, &s.name, &s.values, &[&angle])?;
            self.str_attr(&ds, "units", &s.units)?;
            self.str_attr(&ds, "long_name", &s.long_name)?;
        }
        Ok(())
    }

    /// The coordinate variable `v` of the layout table ([`layout`]).
    fn coordinate_of(
        &mut self,
        g: &h5::Group,
        v: layout::Variable,
        values: &[f64],
    ) -> Res<h5::Dataset> {
        self.coordinate(g, v.name, values, v.units, v.long_name)
    }

    /// The auxiliary coordinate `v` of the layout table on the dimension `dim`.
    fn auxiliary(
        &mut self,
        g: &h5::Group,
        v: layout::Variable,
        values: &[f64],
        dim: &h5::Dataset,
    ) -> Res<()> {
        let ds = self.variable(g, v.name, values, &[dim])?;
        self.str_attr(&ds, "units", v.units)?;
        self.str_attr(&ds, "long_name", v.long_name)
    }

    /// A 1-D coordinate variable that is also its own dimension (netCDF "coordinate variable").
    pub(crate) fn coordinate(
        &mut self,
        g: &h5::Group,
        name: &str,
        values: &[f64],
        units: &str,
        long_name: &str,
    ) -> Res<h5::Dataset> {
        let ds = g
            .new_dataset_builder()
            .with_data(values)
            .create(name)
            .map_err(self.err(format!("coordinate {name}")))?;
        self.make_scale(&ds, name)?;
        self.str_attr(&ds, "units", units)?;
        self.str_attr(&ds, "long_name", long_name)?;
        Ok(ds)
    }

    fn make_scale(&mut self, ds: &h5::Dataset, name: &str) -> Res<()> {
        let cname = CString::new(name).expect("validated names contain no NUL");
        let status = {
            let _lock = hdf5_metno_sys::LOCK.lock();
            // SAFETY: `ds` is an open dataset for the duration of the call, `cname` a valid C
            // string; the library-wide lock serialises HDF5 calls as hdf5-metno does.
            unsafe { H5DSset_scale(ds.id(), cname.as_ptr()) }
        };
        if status < 0 {
            return Err(self.hl_error(format!("H5DSset_scale on '{name}'")));
        }
        let id = self.next_dimid;
        self.next_dimid += 1;
        ds.new_attr::<i32>()
            .shape(())
            .create("_Netcdf4Dimid")
            .and_then(|a| a.write_scalar(&id))
            .map_err(self.err(format!("_Netcdf4Dimid of '{name}'")))
    }

    /// A 1-D data variable along the given dimension scales.
    pub(crate) fn variable(
        &mut self,
        g: &h5::Group,
        name: &str,
        values: &[f64],
        dims: &[&h5::Dataset],
    ) -> Res<h5::Dataset> {
        let ds = g
            .new_dataset_builder()
            .with_data(values)
            .create(name)
            .map_err(self.err(format!("variable {name}")))?;
        self.attach(&ds, dims, name)?;
        Ok(ds)
    }

    fn attach(&self, ds: &h5::Dataset, scales: &[&h5::Dataset], name: &str) -> Res<()> {
        for (axis, scale) in scales.iter().enumerate() {
            let status = {
                let _lock = hdf5_metno_sys::LOCK.lock();
                // SAFETY: both datasets are open; axis < rank (the caller passes one scale per
                // axis); calls serialised by the library-wide lock.
                unsafe { H5DSattach_scale(ds.id(), scale.id(), axis as c_uint) }
            };
            if status < 0 {
                return Err(self.hl_error(format!("H5DSattach_scale on '{name}' axis {axis}")));
            }
        }
        Ok(())
    }

    fn hl_error(&self, context: String) -> OutputError {
        OutputError::Hdf5 {
            path: self.path.clone(),
            context,
            source: h5::Error::from("the HDF5 dimension-scale call failed"),
        }
    }

    pub(crate) fn scalar(
        &self,
        g: &h5::Group,
        name: &str,
        v: f64,
        units: &str,
        long: &str,
    ) -> Res<()> {
        let ds = g
            .new_dataset::<f64>()
            .shape(())
            .create(name)
            .and_then(|d| d.write_scalar(&v).map(|_| d))
            .map_err(self.err(format!("scalar {name}")))?;
        self.str_attr(&ds, "units", units)?;
        self.str_attr(&ds, "long_name", long)
    }

    pub(crate) fn str_attr(&self, loc: &h5::Location, name: &str, value: &str) -> Res<()> {
        let v = vlen(value);
        loc.new_attr::<VarLenUnicode>()
            .shape(())
            .create(name)
            .and_then(|a| a.write_scalar(&v))
            .map_err(self.err(format!("attribute {name}")))
    }

    pub(crate) fn f64_attr(&self, loc: &h5::Location, name: &str, value: f64) -> Res<()> {
        loc.new_attr::<f64>()
            .shape(())
            .create(name)
            .and_then(|a| a.write_scalar(&value))
            .map_err(self.err(format!("attribute {name}")))
    }
}

/// Text as an HDF5 variable-length UTF-8 string (h5py and xarray read it as `str`). NUL bytes,
/// which C strings cannot hold, are replaced by U+FFFD.
fn vlen(s: &str) -> VarLenUnicode {
    let clean = s.replace('\0', "\u{FFFD}");
    clean
        .parse()
        .expect("a string without NUL is a valid VarLenUnicode")
}
