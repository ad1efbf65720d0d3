//! The film fields on the cylindrical bearing surface (or, for a deformable bearing, the shaft
//! and housing meshes: [`write_bodies`]) as a VTKHDF group, so that pyvista
//! (`pyvista.read(path, force_ext=".vtkhdf")`) and ParaView (VTKHDF reader) show the pressure
//! where it acts.
//!
//! VTKHDF (VTK's HDF5 format, version 2.x; spec: docs.vtk.org, "VTKHDF format specification")
//! keeps a VTK dataset in a root group `/VTKHDF`; groups outside it are ignored by the reader,
//! which lets the netCDF groups of the same file live beside it. We write a temporal
//! `UnstructuredGrid` of quadrilaterals:
//!
//! ```text
//!   point p(i, j) = i·n_z + j          x = R cos θ_i,  y = R sin θ_i,  z = z_j      (m)
//!
//!   z_{j+1}  p(i,j+1) ──── p(i+1,j+1)      quad (i, j), i = 0 … n_θ−1, j = 0 … n_z−2,
//!             │               │            corners in this order (normal e_θ × e_z = +e_r,
//!   z_j      p(i,j) ─────── p(i+1,j)       outward); i+1 wraps to 0: the surface is closed
//!            θ_i            θ_{i+1}        in θ without duplicated seam points.
//! ```
//!
//! Point order is the (θ, z) row-major order of the fields, so point data of instant k is
//! `field[k, :, :]` flattened. Geometry and topology are stored once; the `Steps` group makes
//! every instant a time step (`Steps/Values` = time in s) whose point data starts at
//! `k · n_points` of the flattened (instant, point) arrays (`Steps/PointDataOffsets/<name>`), while
//! the point, cell and connectivity offsets stay 0 (geometry reused).
//!
//! ```text
//! /VTKHDF                     attrs Version = [2, 2], Type = "UnstructuredGrid"
//!   NumberOfPoints [1], NumberOfCells [1], NumberOfConnectivityIds [1]      (int64)
//!   Points [n_points, 3] (f64), Connectivity [4 n_cells], Offsets [n_cells+1] (int64),
//!   Types [n_cells] (uint8, VTK_QUAD = 9)
//!   PointData/<field> [n_steps · n_points]
//!   Steps/   attr NSteps; Values [n_steps]; PartOffsets, NumberOfParts, PointOffsets,
//!            CellOffsets, ConnectivityIdOffsets [n_steps]; PointDataOffsets/<field> [n_steps]
//! ```

use hdf5_metno as h5;
use hdf5_metno::types::FixedAscii;

use super::{FieldSnapshots, Geometry, Method};

/// VTK cell type id of a linear quadrilateral (vtkCellType.h).
const VTK_QUAD: u8 = 9;

/// Number of surface points for a grid of `n_theta × n_z` nodes.
pub fn surface_point_count(n_theta: usize, n_z: usize) -> usize {
    n_theta * n_z
}

/// Number of quadrilaterals (the surface is closed in θ).
pub fn surface_cell_count(n_theta: usize, n_z: usize) -> usize {
    n_theta * (n_z - 1)
}

/// Writes `/VTKHDF` into `file` from the fields of `method`. The caller has validated the fields
/// (grid sizes ≥ 3 × 2, shapes consistent).
pub fn write_surface(
    file: &h5::File,
    geometry: &Geometry,
    method: Method,
    f: &FieldSnapshots,
) -> h5::Result<()> {
    let n_points = surface_point_count(f.theta.len(), f.z.len());
    let about = format!(
        "film fields of the {} solution on the bearing surface r = R = {} m; one time step per \
         stored instant (Steps/Values, s)",
        method.as_str(),
        geometry.radius
    );
    let root = create_root(file, &about)?;

    let (points, connectivity) = surface_mesh(geometry, f);
    write_quad_topology(&root, &points, &connectivity)?;

    let point_data = root.create_group("PointData")?;
    for fld in &f.fields {
        // Row-major (instant, θ, z) flattened is (instant, point): exactly the layout wanted.
        let flat: Vec<f64> = fld.values.iter().copied().collect();
        let mut b = point_data.new_dataset_builder();
        if h5::filters::deflate_available() {
            b = b.chunk(n_points).shuffle().deflate(4);
        }
        b.with_data(&flat[..]).create(fld.name.as_str())?;
    }

    write_surface_steps(&root, f, n_points)?;
    Ok(())
}

/// The `/VTKHDF` group of an `UnstructuredGrid` (VTKHDF version 2.2) with its `description`.
fn create_root(file: &h5::File, about: &str) -> h5::Result<h5::Group> {
    let root = file.create_group("VTKHDF")?;
    root.new_attr::<i64>()
        .shape(2)
        .create("Version")?
        .write(&[2i64, 2])?;
    let kind: FixedAscii<16> = FixedAscii::from_ascii(b"UnstructuredGrid")
        .map_err(|e| h5::Error::from(e.to_string().as_str()))?;
    root.new_attr::<FixedAscii<16>>()
        .shape(())
        .create("Type")?
        .write_scalar(&kind)?;
    let about: hdf5_metno::types::VarLenUnicode = about.parse().expect("no NUL");
    root.new_attr::<hdf5_metno::types::VarLenUnicode>()
        .shape(())
        .create("description")?
        .write_scalar(&about)?;
    Ok(root)
}

/// The film surface r = R as points (θ outer, z inner; x y z, m) and its quads, closed in θ.
fn surface_mesh(geometry: &Geometry, f: &FieldSnapshots) -> (ndarray::Array2<f64>, Vec<i64>) {
    let (nth, nz) = (f.theta.len(), f.z.len());
    let n_points = surface_point_count(nth, nz);
    let n_cells = surface_cell_count(nth, nz);
    let mut points = ndarray::Array2::<f64>::zeros((n_points, 3));
    for (i, th) in f.theta.iter().enumerate() {
        for (j, z) in f.z.iter().enumerate() {
            let p = i * nz + j;
            points[[p, 0]] = geometry.radius * th.cos();
            points[[p, 1]] = geometry.radius * th.sin();
            points[[p, 2]] = *z;
        }
    }
    let mut connectivity = Vec::with_capacity(4 * n_cells);
    for i in 0..nth {
        let next = (i + 1) % nth;
        for j in 0..nz - 1 {
            connectivity.extend_from_slice(&[
                (i * nz + j) as i64,
                (next * nz + j) as i64,
                (next * nz + j + 1) as i64,
                (i * nz + j + 1) as i64,
            ]);
        }
    }
    (points, connectivity)
}

/// `Steps`: one time step per stored instant (its time in `Values`), every step on the same
/// single part, points and cells, and each field's data `n_points` further on.
fn write_surface_steps(root: &h5::Group, f: &FieldSnapshots, n_points: usize) -> h5::Result<()> {
    let nt = f.time.len();
    let steps = root.create_group("Steps")?;
    steps
        .new_attr::<i64>()
        .shape(())
        .create("NSteps")?
        .write_scalar(&(nt as i64))?;
    let step_ds = |name: &str, data: &[i64]| -> h5::Result<()> {
        steps.new_dataset_builder().with_data(data).create(name)?;
        Ok(())
    };
    steps
        .new_dataset_builder()
        .with_data(&f.time[..])
        .create("Values")?;
    let zeros = vec![0i64; nt];
    step_ds("PartOffsets", &zeros)?;
    step_ds("NumberOfParts", &vec![1i64; nt])?;
    step_ds("PointOffsets", &zeros)?;
    step_ds("CellOffsets", &zeros)?;
    step_ds("ConnectivityIdOffsets", &zeros)?;
    let pdo = steps.create_group("PointDataOffsets")?;
    let data_offsets: Vec<i64> = (0..nt as i64).map(|k| k * n_points as i64).collect();
    for fld in &f.fields {
        pdo.new_dataset_builder()
            .with_data(&data_offsets[..])
            .create(fld.name.as_str())?;
    }
    Ok(())
}

/// Writes `/VTKHDF` into `file`: the plane-strain bodies of a deformable bearing (shaft and
/// housing, `super::elastic`) as one static `UnstructuredGrid` of quadrilaterals (one part):
///
/// ```text
///   points: body 0's nodes, then body 1's, … (x, y, z = 0), m, undeformed;
///   cells:  each body's quads with its node numbers shifted by the points before it;
///   PointData: displacement [n, 3] (u_x, u_y, 0) m (ParaView's "Warp By Vector" draws the
///              deformed bodies), stress_xx, stress_yy, stress_xy, stress_zz, von_mises_stress,
///              radial_stress, hoop_stress (polar frame about the bore centre) Pa;
///   CellData:  body (0, 1, … in the order given: shaft 0, housing 1).
/// ```
///
/// The bodies share the film-surface radius but not its nodes (each has its own ring at r = R),
/// so the grid holds two coincident rings there, one per body.
pub fn write_bodies(file: &h5::File, bodies: &[super::BodyField]) -> h5::Result<()> {
    let n_points: usize = bodies.iter().map(|b| b.points.len()).sum();
    let n_cells: usize = bodies.iter().map(|b| b.cells.len()).sum();
    let names: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();
    let about = format!(
        "plane-strain bodies of the deformable bearing ({}; CellData body = index in this \
         list), undeformed points (m), nodal displacement (m) and stresses (Pa)",
        names.join(", ")
    );
    let root = create_root(file, &about)?;

    let mut points = ndarray::Array2::<f64>::zeros((n_points, 3));
    let mut displacement = ndarray::Array2::<f64>::zeros((n_points, 3));
    let mut connectivity = Vec::with_capacity(4 * n_cells);
    let mut body_id = Vec::with_capacity(n_cells);
    let scalar_names = [
        "stress_xx",
        "stress_yy",
        "stress_xy",
        "stress_zz",
        "von_mises_stress",
        "radial_stress",
        "hoop_stress",
    ];
    let mut scalars: Vec<Vec<f64>> = vec![Vec::with_capacity(n_points); scalar_names.len()];
    let mut first = 0usize;
    for (ib, b) in bodies.iter().enumerate() {
        for (k, p) in b.points.iter().enumerate() {
            let row = first + k;
            points[[row, 0]] = p[0];
            points[[row, 1]] = p[1];
            displacement[[row, 0]] = b.displacement[k][0];
            displacement[[row, 1]] = b.displacement[k][1];
            let [xx, yy, xy, zz] = b.stress[k];
            let [sr, st] = b.polar_stress(k);
            for (v, x) in scalars
                .iter_mut()
                .zip([xx, yy, xy, zz, b.von_mises(k), sr, st])
            {
                v.push(x);
            }
        }
        for cell in &b.cells {
            connectivity.extend(cell.iter().map(|&n| (first + n) as i64));
            body_id.push(ib as i64);
        }
        first += b.points.len();
    }
    write_quad_topology(&root, &points, &connectivity)?;
    let point_data = root.create_group("PointData")?;
    point_data
        .new_dataset_builder()
        .with_data(displacement.view())
        .create("displacement")?;
    for (name, values) in scalar_names.iter().zip(&scalars) {
        point_data
            .new_dataset_builder()
            .with_data(&values[..])
            .create(*name)?;
    }
    let cell_data = root.create_group("CellData")?;
    cell_data
        .new_dataset_builder()
        .with_data(&body_id[..])
        .create("body")?;
    Ok(())
}

/// The UnstructuredGrid topology of `n_cells` = connectivity / 4 quads over `points` (one row
/// per point, x y z): the counts, Points, Connectivity, Offsets and Types datasets of the
/// VTKHDF layout (module docs).
fn write_quad_topology(
    root: &h5::Group,
    points: &ndarray::Array2<f64>,
    connectivity: &[i64],
) -> h5::Result<()> {
    let n_cells = connectivity.len() / 4;
    let offsets: Vec<i64> = (0..=n_cells as i64).map(|c| 4 * c).collect();
    let types = vec![VTK_QUAD; n_cells];
    let ds_i64 = |name: &str, data: &[i64]| -> h5::Result<()> {
        root.new_dataset_builder().with_data(data).create(name)?;
        Ok(())
    };
    ds_i64("NumberOfPoints", &[points.nrows() as i64])?;
    ds_i64("NumberOfCells", &[n_cells as i64])?;
    ds_i64("NumberOfConnectivityIds", &[connectivity.len() as i64])?;
    root.new_dataset_builder()
        .with_data(points.view())
        .create("Points")?;
    ds_i64("Connectivity", connectivity)?;
    ds_i64("Offsets", &offsets)?;
    root.new_dataset_builder()
        .with_data(&types[..])
        .create("Types")?;
    Ok(())
}
