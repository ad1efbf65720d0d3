"""Plot a jbearing result file with xarray, matplotlib and pyvista.

    python -m venv .venv && .venv/bin/pip install -r examples/python/requirements.txt
    .venv/bin/python examples/python/plot_case.py results/compressor_main.h5 --out plots/

The whole file is opened as one xarray DataTree (`xr.open_datatree`): the method groups share
one crank-angle grid, so `tree["rigorous"].dataset - tree["mobility"].dataset` compares them
sample by sample, `.sel(crank_angle=90)` picks an exact crank angle and
`tree["rigorous/fields"].dataset.sel(field_crank_angle=…)` a stored field instant.

Writes CASE_series.png (the cycle: eccentricity ratio, h_min, flow and power loss, both
methods, and the mobility-minus-rigorous difference of h_min) and CASE_pressure.png (the film pressure over the unrolled bearing surface at the
instant of the highest peak pressure), and prints what the file holds. With --surface-png, also
CASE_surface.png (the same pressure on the 3-D bearing surface, rendered off screen by pyvista);
with --show, opens that surface in a pyvista window with a slider over the stored instants.
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only; --show uses pyvista's own window
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pyvista as pv  # noqa: E402
import xarray as xr  # noqa: E402

# What each panel shows: variable name, display factor, axis label.
PANELS = [
    ("eccentricity_ratio", 1.0, "eccentricity ratio [-]"),
    ("min_film_thickness", 1e6, "h_min [µm]"),
    ("supply_flow", 1e6, "supply flow [cm³/s]"),
    ("power_loss", 1.0, "power loss [W]"),
]
STYLE = {"rigorous": dict(color="tab:blue"), "mobility": dict(color="tab:red", ls="--")}


def open_methods(path):
    """The whole file as a DataTree, and the method groups present in it as Datasets."""
    # phony_dims: the VTKHDF group (for pyvista) has no netCDF dimensions of its own.
    tree = xr.open_datatree(path, engine="h5netcdf", phony_dims="sort")
    return tree, {m: tree[m].dataset for m in tree.attrs["methods"].split()}


def plot_series(methods, case, out):
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex=True, constrained_layout=True)
    for ax, (name, factor, label) in zip(axes.flat, PANELS):
        for method, ds in methods.items():
            if name in ds:
                ax.plot(ds["crank_angle"], ds[name] * factor, label=method, **STYLE[method])
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend()
    if {"rigorous", "mobility"} <= set(methods):
        # Both methods sample the same crank angles: the difference is one line of xarray.
        diff = (methods["mobility"]["min_film_thickness"]
                - methods["rigorous"]["min_film_thickness"]) * 1e6
        twin = axes.flat[1].twinx()
        twin.plot(diff["crank_angle"], diff, color="grey", lw=0.8, label="mobility − rigorous")
        twin.set_ylabel("Δh_min [µm]", color="grey")
    # The crank grid stops one step short of the cycle (the periodic point is not repeated).
    ca = methods[next(iter(methods))]["crank_angle"].values
    cycle = float(ca[-1] + (ca[1] - ca[0]))
    for ax in axes[1]:
        ax.set_xlabel("crank angle [deg]")
        ax.set_xticks(np.arange(0, cycle + 1, 90))
    fig.suptitle(f"{case}: rigorous and mobility over the cycle")
    path = out / f"{case}_series.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_pressure(fields, case, out):
    snap = fields["pressure"].isel(field_crank_angle=peak_step(fields))
    fig, ax = plt.subplots(figsize=(9, 4), constrained_layout=True)
    mesh = ax.pcolormesh(np.degrees(snap["theta"]), snap["z"] * 1e3, snap.T / 1e6,
                         shading="gouraud", cmap="viridis")
    fig.colorbar(mesh, ax=ax, label="film pressure [MPa]")
    ax.set_xlabel("θ [deg] (from +x towards +y, bearing frame)")
    ax.set_ylabel("z [mm]")
    ax.set_title(f"{case}: pressure at crank angle {float(snap['field_crank_angle']):.0f}°, "
                 f"peak {float(snap.max()) / 1e6:.2f} MPa")
    path = out / f"{case}_pressure.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def peak_step(fields):
    """Index of the stored instant with the highest peak pressure."""
    return int(fields["pressure"].max(dim=("theta", "z")).argmax(dim="field_crank_angle"))


def surface_at(path, step):
    """The VTKHDF surface of the file at one stored instant, via pyvista."""
    reader = pv.get_reader(path, force_ext=".vtkhdf").reader
    reader.UpdateInformation()
    reader.SetStep(step)
    reader.Update()
    return pv.wrap(reader.GetOutput())


def surface_png(path, fields, case, out):
    """The pressure at its peak instant on the bearing surface, drawn off screen: the surface is
    pushed outwards in proportion to the pressure (0.4 R at the peak) so the pressure hill shows
    in 3-D, with the undeformed bearing as a grey wireframe."""
    k = peak_step(fields)
    mesh = surface_at(path, k)
    radial = mesh.points.copy()
    radial[:, 2] = 0.0
    r = np.linalg.norm(radial, axis=1, keepdims=True)
    p = mesh.point_data["pressure"]
    mesh["lift"] = radial / r * (0.4 * r * (p / p.max())[:, None])
    warped = mesh.warp_by_vector("lift")
    warped["pressure_MPa"] = p / 1e6
    plotter = pv.Plotter(off_screen=True, window_size=(1000, 800))
    plotter.add_mesh(mesh, style="wireframe", color="grey", opacity=0.3)
    plotter.add_mesh(warped, scalars="pressure_MPa", cmap="viridis",
                     scalar_bar_args={"title": "film pressure [MPa]", "fmt": "%.1f"})
    plotter.add_text(f"{case}: crank angle {float(fields['field_crank_angle'][k]):.0f} deg",
                     font_size=12)
    # Look at the pressure hill from outside, a little above the mid-plane.
    peak = radial[int(np.argmax(p))] / r[int(np.argmax(p))]
    R = float(r.max())
    plotter.camera_position = [(6 * R * peak[0], 6 * R * peak[1], 3 * R), (0, 0, 0), (0, 0, 1)]
    path_png = out / f"{case}_surface.png"
    plotter.screenshot(path_png)
    plotter.close()
    return path_png


def show_surface(path):
    """Interactive 3-D view: the pressure on the bearing surface, one slider step per instant."""
    reader = pv.get_reader(path, force_ext=".vtkhdf").reader
    reader.UpdateInformation()
    n = reader.GetNumberOfSteps()
    plotter = pv.Plotter()

    def show(step):
        reader.SetStep(int(round(step)))
        reader.Update()
        mesh = pv.wrap(reader.GetOutput())
        plotter.add_mesh(mesh, scalars="pressure", name="surface", cmap="viridis")

    show(0)
    plotter.add_slider_widget(show, [0, n - 1], value=0, title="stored instant")
    plotter.show()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("file", type=Path, help="a CASE.h5 written by jbearing")
    ap.add_argument("--out", type=Path, default=Path("."), help="directory for the PNGs")
    ap.add_argument("--show", action="store_true", help="open the 3-D pressure surface")
    ap.add_argument("--surface-png", action="store_true",
                    help="also render CASE_surface.png off screen (needs OpenGL or OSMesa)")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    tree, methods = open_methods(args.file)
    root = tree
    case = root.attrs["case_name"]
    print(f"case {case}: jbearing {root.attrs['jbearing_version']} "
          f"({root.attrs['git_commit']}), wall time {root.attrs['wall_time_s']:.1f} s")
    print(f"methods: {', '.join(methods)}")
    print(plot_series(methods, case, args.out))

    summary = tree["summary"].dataset
    print(summary.to_dataframe().T.to_string())
    for method in methods:
        row = summary.sel(solution_method=method)
        print(f"{method}: cycle minimum of h_min {float(row['min_film_thickness_min']) * 1e6:.3f} µm")

    if "rigorous" in methods:
        fields = tree["rigorous/fields"].dataset
        print(plot_pressure(fields, case, args.out))
        surface = pv.read(args.file, force_ext=".vtkhdf")
        print(f"surface: {surface.n_points} points, {surface.n_cells} cells, "
              f"arrays {list(surface.point_data.keys())}")
        if args.surface_png:
            print(surface_png(args.file, fields, case, args.out))
        if args.show:
            show_surface(args.file)


if __name__ == "__main__":
    main()
