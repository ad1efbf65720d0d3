"""Checks a jbearing HDF5 file the way a user's Python would read it.

Run by tests/output.rs in a fresh virtualenv (examples/python/requirements.txt):

    python check_output.py CASE.h5 CASE.expected

CASE.expected holds what the Rust side wrote, one line per array: `key v1 v2 ...` (f64 printed
shortest-round-trip, so the comparison is exact). Asserts named dimensions and coordinates,
units, the values read back through xarray (h5netcdf engine), and that pyvista reads the VTKHDF
surface with one point per (theta, z) node and the pressure of every stored instant.
Prints one line per check and exits non-zero on the first failure.
"""

import sys
import warnings

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
        check(tuple(ds.dims) == ("time",), f"{method}: one dimension, named time")
        check("time" in ds.coords and "crank_angle" in ds.coords,
              f"{method}: time and crank_angle are coordinates")
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
            check(v.dims == ("time",) and v.attrs.get("units") and v.attrs.get("long_name"),
                  f"{method}/{name}: dims (time,), units and long_name")
            check(np.array_equal(v.values, exp[f"{method}/{name}"]), f"{method}/{name}: values")
        check(ds["load_x"].attrs["units"] == "N" and ds["min_film_thickness"].attrs["units"] == "m"
              and ds["supply_flow"].attrs["units"] == "m3 s-1", f"{method}: SI units")

    f = xr.open_dataset(path, engine="h5netcdf", group="rigorous/fields")
    nt, nth, nz = (len(exp["rigorous/fields/time"]), len(exp["rigorous/fields/theta"]),
                   len(exp["rigorous/fields/z"]))
    check(dict(f.sizes) == {"time": nt, "theta": nth, "z": nz}, "fields: sizes of time, theta, z")
    check(f["pressure"].dims == ("time", "theta", "z"), "pressure dims (time, theta, z)")
    check(f["theta"].attrs["units"] == "rad" and f["z"].attrs["units"] == "m"
          and f["pressure"].attrs["units"] == "Pa", "fields: units")
    for c in ("time", "theta", "z"):
        check(np.array_equal(f[c].values, exp[f"rigorous/fields/{c}"]), f"fields: {c} values")
    for name in ("pressure", "film_thickness"):
        check(np.array_equal(f[name].values.ravel(), exp[f"rigorous/fields/{name}"]),
              f"fields: {name} values")
    # Label-based selection works because the dimensions carry coordinates.
    p = f["pressure"].sel(theta=np.pi, z=0.0, method="nearest")
    check(p.dims == ("time",) and p.sizes["time"] == nt, "sel by theta and z gives a time series")

    s = xr.open_dataset(path, engine="h5netcdf", group="summary")
    check(list(s["method"].values) == ["rigorous", "mobility"], "summary: method coordinate")
    for key, vals in exp.items():
        if key.startswith("summary/"):
            name = key.split("/", 1)[1]
            check(np.array_equal(s[name].values, vals, equal_nan=True), f"summary/{name} values")

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


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
