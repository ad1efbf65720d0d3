"""Heat maps of a two-key sweep from `jbearing merge`'s file: h_min and power loss of the
rigorous (and mobility) method over the two swept keys.

    python examples/python/sweep_heatmap.py results/rod_sweep.nc [--out rod_sweep.png]

The merged file has one `case` dimension; the swept case-file keys are its coordinates
(`radial_clearance_m`, `supply_temperature_c`, ...). `set_xindex` makes one of them selectable,
`set_index(case=[a, b]).unstack("case")` turns the factorial sweep into a 2-D grid.
"""

import argparse
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("merged", help="the file written by jbearing merge")
    ap.add_argument("--out", default=None, help="PNG to write (default: beside the file)")
    args = ap.parse_args()

    ds = xr.open_dataset(args.merged, engine="h5netcdf")
    keys = [k for k in ds.coords if ds[k].dims == ("case",) and "sweep_key" in ds[k].attrs]
    if len(keys) != 2:
        print(f"need a sweep over two keys, found {keys}", file=sys.stderr)
        return 1
    bad = ds.status.values[ds.status.values != "ok"]
    for s in bad:
        print(f"not ok: {s}", file=sys.stderr)

    # One key selectable by value: the cases at the first value of the first key.
    first = ds.set_xindex(keys[0]).sel({keys[0]: ds[keys[0]].values[0]})
    print(f"{keys[0]} = {ds[keys[0]].values[0]}: {first.sizes['case']} cases")

    grid = ds.set_index(case=keys).unstack("case")
    scale = {"min_film_thickness_min": (1e6, "h_min, cycle minimum [µm]"),
             "power_loss_mean": (1.0, "power loss, cycle mean [W]"),
             "effective_temperature": (1.0, "effective temperature [°C]")}
    names = [n for n in scale if n in grid]
    methods = [m for m in grid.solution_method.values
               if np.isfinite(grid[names[0]].sel(solution_method=m)).any()]
    fig, axes = plt.subplots(len(methods), len(names), figsize=(4.2 * len(names), 3.6 * len(methods)),
                             squeeze=False, constrained_layout=True)
    x, y = keys[1], keys[0]
    for i, m in enumerate(methods):
        for j, n in enumerate(names):
            f, label = scale[n]
            v = grid[n].sel(solution_method=m).transpose(y, x) * f
            ax = axes[i][j]
            im = ax.pcolormesh(np.arange(v.sizes[x]), np.arange(v.sizes[y]), v.values, shading="nearest")
            for (a, b), val in np.ndenumerate(v.values):
                ax.text(b, a, f"{val:.3g}", ha="center", va="center", color="w", fontsize=9)
            ax.set_xticks(range(v.sizes[x]), [f"{t:g}" for t in v[x].values])
            ax.set_yticks(range(v.sizes[y]), [f"{t:g}" for t in v[y].values])
            ax.set_xlabel(x)
            ax.set_ylabel(y)
            ax.set_title(f"{m}: {label}", fontsize=10)
            fig.colorbar(im, ax=ax)
    out = args.out or args.merged.rsplit(".", 1)[0] + "_heatmap.png"
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
