"""Checks a jbearing HDF5 file the way a user's Python would read it.

Run by tests/output.rs in a fresh virtualenv (examples/python/requirements.txt):

    python check_output.py CASE.h5 CASE.expected

CASE.expected holds what the Rust side wrote, one line per array: `key v1 v2 ...` (f64 printed
shortest-round-trip, so the comparison is exact). Asserts named dimensions and coordinates,
units, the values read back through xarray (h5netcdf engine), the whole file as one xarray
DataTree with both engines (h5netcdf, netcdf4) selected by method, by crank angle and by field
instant, the CF-1.10 metadata (cf_xarray), and that pyvista reads the VTKHDF surface with one
point per (theta, z) node and the pressure of every stored instant.
Prints one line per check and exits non-zero on the first failure.
"""

import sys
import warnings

import cf_xarray  # noqa: F401  (registers the .cf accessor)
import numpy as np
import pyvista as pv
import xarray as xr


def load_expected(path):
    out = {}
    with open(path) as f:
        for line in f:
            key, *vals = line.split()
            out[key] = np.array([float(v) for v in vals])
    return out


def check(cond, what):
    if not cond:
        raise AssertionError(what)
    print("ok:", what)


def main(path, expected_path):
    # Any warning from the readers (phony dims, undecodable attributes, ...) is a failure.
    warnings.simplefilter("error")
    exp = load_expected(expected_path)

    root = xr.open_dataset(path, engine="h5netcdf")
    check(root.attrs["methods"] == "rigorous mobility", "root attrs list the methods")
    check("version" in root.attrs["case_text"], "case text stored as given")
    for key in ("jbearing_version", "git_commit", "wall_time_s", "started_utc"):
        check(key in root.attrs, f"run info '{key}' present")
    check(root["radial_clearance"].attrs["units"] == "m", "clearance has units m")

    inputs = xr.open_dataset(path, engine="h5netcdf", group="input_files")
    check(list(inputs["file"].values) == ["loads/fixture.csv"]
          and str(inputs["text"].values[0]).startswith("crank_angle_deg,"),
          "input files stored verbatim with their paths")

    params = xr.open_dataset(path, engine="h5netcdf", group="parameters")
    check(params["viscosity"].attrs["units"] == "Pa s", "parameter units")
    check(str(params["cavitation_model"].values) == "fixture (Gumbel half film)",
          "text parameter read back")

    for method in ("rigorous", "mobility"):
        ds = xr.open_dataset(path, engine="h5netcdf", group=method)
        check(tuple(ds.dims) == ("crank_angle",), f"{method}: one dimension, named crank_angle")
        check("time" in ds.coords and "crank_angle" in ds.indexes,
              f"{method}: crank_angle indexes, time is a coordinate")
        check(ds["time"].dtype == np.float64, f"{method}: time stays float seconds")
        check(ds["time"].attrs["units"] == "s", f"{method}: time units s")
        check(ds["crank_angle"].attrs["units"] == "degree", f"{method}: crank angle in degree")
        check(np.array_equal(ds["time"].values, exp[f"{method}/time"]), f"{method}: time values")
        check(np.array_equal(ds["crank_angle"].values, exp[f"{method}/crank_angle"]),
              f"{method}: crank angle values")
        series = sorted(k.split("/", 1)[1] for k in exp
                        if k.startswith(method + "/") and "/fields/" not in k
                        and k not in (f"{method}/time", f"{method}/crank_angle"))
        check(sorted(ds.data_vars) == series, f"{method}: exactly the written series")
        for name in series:
            v = ds[name]
            check(v.dims == ("crank_angle",) and v.attrs.get("units") and v.attrs.get("long_name"),
                  f"{method}/{name}: dims (crank_angle,), units and long_name")
            check(np.array_equal(v.values, exp[f"{method}/{name}"]), f"{method}/{name}: values")
        check(ds["load_x"].attrs["units"] == "N" and ds["min_film_thickness"].attrs["units"] == "m"
              and ds["supply_flow"].attrs["units"] == "m3 s-1", f"{method}: SI units")

    f = xr.open_dataset(path, engine="h5netcdf", group="rigorous/fields")
    nt, nth, nz = (len(exp["rigorous/fields/field_time"]), len(exp["rigorous/fields/theta"]),
                   len(exp["rigorous/fields/z"]))
    check(dict(f.sizes) == {"field_crank_angle": nt, "theta": nth, "z": nz},
          "fields: sizes of field_crank_angle, theta, z")
    check(f["pressure"].dims == ("field_crank_angle", "theta", "z"),
          "pressure dims (field_crank_angle, theta, z)")
    check(f["theta"].attrs["units"] == "rad" and f["z"].attrs["units"] == "m"
          and f["pressure"].attrs["units"] == "Pa", "fields: units")
    for c in ("field_time", "field_crank_angle", "theta", "z"):
        check(np.array_equal(f[c].values, exp[f"rigorous/fields/{c}"]), f"fields: {c} values")
    for name in ("pressure", "film_thickness"):
        check(np.array_equal(f[name].values.ravel(), exp[f"rigorous/fields/{name}"]),
              f"fields: {name} values")
    # Label-based selection works because the dimensions carry coordinates.
    p = f["pressure"].sel(theta=np.pi, z=0.0, method="nearest")
    check(p.dims == ("field_crank_angle",) and p.sizes["field_crank_angle"] == nt,
          "sel by theta and z gives a series over the stored instants")

    s = xr.open_dataset(path, engine="h5netcdf", group="summary")
    check(list(s["solution_method"].values) == ["rigorous", "mobility"],
          "summary: solution_method coordinate")
    for key, vals in exp.items():
        if key.startswith("summary/"):
            name = key.split("/", 1)[1]
            check(np.array_equal(s[name].values, vals, equal_nan=True), f"summary/{name} values")

    check_datatree(path, exp)
    check_cf(path)

    # pyvista: the VTKHDF group of the same file.
    mesh = pv.read(path, force_ext=".vtkhdf")
    check(mesh.n_points == nth * nz, f"pyvista: {nth} x {nz} = {nth * nz} surface points")
    check(mesh.n_cells == nth * (nz - 1), "pyvista: closed ring of quads")
    radius = float(root["radius"].values)
    r = np.hypot(mesh.points[:, 0], mesh.points[:, 1])
    check(np.allclose(r, radius, rtol=1e-12), "pyvista: points on the cylinder r = R")
    check("pressure" in mesh.point_data, "pyvista: pressure point array")
    p_all = exp["rigorous/fields/pressure"].reshape(nt, nth * nz)
    check(np.array_equal(mesh.point_data["pressure"], p_all[0]), "pyvista: pressure of step 0")
    reader = pv.get_reader(path, force_ext=".vtkhdf").reader
    reader.UpdateInformation()
    check(reader.GetNumberOfSteps() == nt, f"pyvista/VTK: {nt} time steps")
    for k in range(nt):
        reader.SetStep(k)
        reader.Update()
        step = pv.wrap(reader.GetOutput())
        check(np.array_equal(step.point_data["pressure"], p_all[k]), f"VTK step {k}: pressure")
    print("all checks passed")


def check_datatree(path, exp):
    """The whole file as one DataTree, with both engines: every group aligned with its parents,
    selections by method, by exact crank angle and by field instant, and rigorous - mobility in
    one line (both methods on the same crank grid)."""
    crank = exp["rigorous/crank_angle"]
    angle = float(crank[len(crank) // 2])  # a whole number of degrees in the fixture
    field_angle = float(exp["rigorous/fields/field_crank_angle"][-1])
    for engine, kwargs in (("h5netcdf", {"phony_dims": "sort"}), ("netcdf4", {})):
        tree = xr.open_datatree(path, engine=engine, **kwargs)
        check({"rigorous", "mobility", "summary", "rigorous/fields"} <= set(
            g.lstrip("/") for g in tree.groups), f"DataTree ({engine}): the groups")
        row = tree["summary"].dataset.sel(solution_method="rigorous")
        check(row["min_film_thickness_min"].size == 1
              and float(row["min_film_thickness_min"]) == exp["summary/min_film_thickness_min"][0],
              f"DataTree ({engine}): sel(solution_method='rigorous') is one row")
        rig = tree["rigorous"].dataset
        mob = tree["mobility"].dataset
        k = int(np.flatnonzero(crank == angle)[0])
        check(float(rig["min_film_thickness"].sel(crank_angle=angle))
              == exp["rigorous/min_film_thickness"][k],
              f"DataTree ({engine}): sel(crank_angle={angle:g}) by exact value")
        diff = rig["min_film_thickness"] - mob["min_film_thickness"]
        check(diff.sizes == {"crank_angle": len(crank)} and not bool(diff.isnull().any()),
              f"DataTree ({engine}): rigorous - mobility aligned on the shared crank grid")
        snap = tree["rigorous/fields"].dataset["pressure"].sel(field_crank_angle=field_angle)
        check(snap.dims == ("theta", "z"),
              f"DataTree ({engine}): sel(field_crank_angle={field_angle:g}) is one instant")


def check_cf(path):
    """CF-1.10 metadata as cf_xarray reads it."""
    root = xr.open_dataset(path, engine="h5netcdf")
    check(root.attrs["Conventions"] == "CF-1.10", "CF: global Conventions")
    for key in ("title", "source", "history"):
        check(bool(root.attrs.get(key)), f"CF: global {key}")
    f = xr.open_dataset(path, engine="h5netcdf", group="rigorous/fields")
    check(f.cf.axes.get("X") == ["theta"] and f.cf.axes.get("Y") == ["z"],
          "CF: theta and z carry axis X and Y")
    params = xr.open_dataset(path, engine="h5netcdf", group="parameters")
    flags = [v for v in params.data_vars.values() if "flag_meanings" in v.attrs]
    check(len(flags) > 0 and all(list(v.attrs["flag_values"]) == [0, 1] for v in flags),
          "CF: every flag has flag_values with its flag_meanings")
    for group in ("rigorous", "mobility", "rigorous/fields", "summary"):
        ds = xr.open_dataset(path, engine="h5netcdf", group=group)
        for name, v in ds.variables.items():
            if v.dtype.kind == "f":
                check("units" in v.attrs and "long_name" in v.attrs,
                      f"CF: {group}/{name} has units and long_name")
    rig = xr.open_dataset(path, engine="h5netcdf", group="rigorous")
    check("from the bearing frame's +x axis" in rig["attitude_angle"].attrs["long_name"],
          "the attitude angle names its reference direction")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
