"""jbearing from Python: dynamically loaded journal bearings with mass-conserving (JFO) cavitation.

The solvers are jbearing's Rust code (the extension module ``jbearing._jbearing``); this layer
builds xarray objects with the names, units and dimensions of the CLI's ``CASE.h5``:

- :func:`run_case` runs a TOML case file exactly as ``jbearing run`` does and returns an
  ``xarray.DataTree`` with the groups of ``CASE.h5`` (root: geometry and run attributes;
  ``parameters``, ``rigorous`` (+ ``rigorous/fields``), ``mobility``, ``summary``,
  ``closed_form``, ``input_files``).
- :func:`inverse_cycle` (load history -> orbit, the finite-difference JFO film) and
  :func:`mobility_cycle` (Booker's mobility method) take the bearing as keyword arguments in SI
  units and numpy arrays for the load history; they write the equivalent case file text (kept
  in the result's ``case_text`` attribute: save it and ``jbearing run`` gives the same numbers)
  and solve it through the same path as :func:`run_case`.
- :func:`closed_form` returns the closed-form static equilibria (the ``closed_form`` group).
- :func:`steady` solves the steady finite-difference Reynolds (JFO) film under a constant load.

Units: SI everywhere (m, Pa s, N, rad/s, Pa); crank angles in degrees, as in the files.
Solves release the GIL; ``progress`` is a callable receiving one dict per event (at most
every 0.1 s within a cycle, and at each cycle's end), or ``True`` for a tqdm bar. Ctrl-C stops
a running solve with ``KeyboardInterrupt`` after its current time step; an exception raised by
the progress callable stops it the same way and is re-raised. Errors are
:class:`JbearingError` subclasses whose attributes carry the Rust error variant's fields and
those of its sources (``kind`` is the variant, ``variants`` the chain of variants outermost
first, ``details`` the whole parsed error; e.g. ``CaseError.line``,
``SolverError.force_residual``, ``SolverError.min_film_thickness`` of a film collapse).
"""

from __future__ import annotations

import json
import math
import os
import re
from pathlib import Path
from typing import Any, Callable, Iterable, Mapping

import numpy as np
import xarray as xr

from . import _jbearing

__all__ = [
    "run_case",
    "solve_case_text",
    "inverse_cycle",
    "mobility_cycle",
    "closed_form",
    "steady",
    "case_toml",
    "JbearingError",
    "CaseError",
    "SolverError",
    "BudgetError",
    "OutputError",
]

__version__ = _jbearing.__version__

JbearingError = _jbearing.JbearingError
CaseError = _jbearing.CaseError
SolverError = _jbearing.SolverError
BudgetError = _jbearing.BudgetError
OutputError = _jbearing.OutputError


# ---------------------------------------------------------------------------------------------
# Errors: the Rust error's Debug form parsed into attributes.


def _parse_debug(text: str) -> Any:
    """Parse Rust's ``{:?}`` of an error (structs, tuples, lists, strings, numbers) into
    dicts / lists / Python scalars. Struct variants become ``{"variant": name, field: value}``,
    a one-field tuple variant wrapping one ``{"variant": name, "source": inner}``."""
    pos = 0

    def ws() -> None:
        nonlocal pos
        while pos < len(text) and text[pos] in " \n\t":
            pos += 1

    def value() -> Any:
        nonlocal pos
        ws()
        c = text[pos]
        if c == '"':
            end = pos + 1
            while text[end] != '"':
                end += 2 if text[end] == "\\" else 1
            s = json.loads(_rust_str_to_json(text[pos : end + 1]))
            pos = end + 1
            return s
        if c == "[" or c == "(":
            close = "]" if c == "[" else ")"
            pos += 1
            items = seq(close)
            return items if c == "[" else tuple(items)
        m = re.compile(r"[-+]?(?:\d[\d_]*\.?\d*(?:[eE][-+]?\d+)?|inf|NaN)(?![A-Za-z0-9_])").match(text, pos)
        if m and m.group(0):
            pos = m.end()
            s = m.group(0)
            if re.fullmatch(r"[-+]?\d+", s):
                return int(s)
            return float(s.replace("NaN", "nan"))
        m = re.compile(r"[A-Za-z_][A-Za-z0-9_:]*").match(text, pos)
        if not m:
            raise ValueError(f"cannot parse {text[pos:pos + 20]!r}")
        name = m.group(0)
        pos = m.end()
        ws()
        if name in ("true", "false"):
            return name == "true"
        if name == "None":
            return None
        if pos < len(text) and text[pos] == "{":
            pos += 1
            out: dict[str, Any] = {"variant": name}
            while True:
                ws()
                if text[pos] == "}":
                    pos += 1
                    return out
                m = re.compile(r"[A-Za-z_][A-Za-z0-9_]*").match(text, pos)
                key = m.group(0)
                pos = m.end()
                ws()
                assert text[pos] == ":"
                pos += 1
                out[key] = value()
                ws()
                if text[pos] == ",":
                    pos += 1
        if pos < len(text) and text[pos] == "(":
            pos += 1
            items = seq(")")
            if name == "Some":
                return items[0]
            if len(items) == 1 and isinstance(items[0], dict):
                inner = dict(items[0])
                return {"variant": name, "source": inner}
            return {"variant": name, "values": items}
        return name

    def seq(close: str) -> list:
        nonlocal pos
        items = []
        while True:
            ws()
            if text[pos] == close:
                pos += 1
                return items
            items.append(value())
            ws()
            if text[pos] == ",":
                pos += 1

    return value()


def _rust_str_to_json(s: str) -> str:
    # Rust escapes \u{XXXX}; JSON wants \uXXXX (surrogate pairs above the BMP).
    def rep(m: re.Match) -> str:
        cp = int(m.group(1), 16)
        if cp < 0x10000:
            return f"\\u{cp:04x}"
        cp -= 0x10000
        return f"\\u{0xD800 + (cp >> 10):04x}\\u{0xDC00 + (cp & 0x3FF):04x}"

    return re.sub(r"\\u\{([0-9a-fA-F]+)\}", rep, s).replace("\\'", "'")


def _flatten(d: dict, out: dict) -> None:
    """The fields of a parsed error and of its sources, outer ones first (``x_variant`` names the
    variant of a nested error in field ``x``)."""
    for k, v in d.items():
        if k == "variant":
            continue
        if isinstance(v, dict) and "variant" in v:
            out.setdefault(f"{k}_variant", v["variant"])
            _flatten(v, out)
        else:
            out.setdefault(k, v)


def _enrich(err: BaseException) -> BaseException:
    """Set the Rust error variant's fields (and those of its sources) as attributes."""
    debug = getattr(err, "debug", None)
    if not isinstance(debug, str):
        return err
    try:
        parsed = _parse_debug(debug)
    except Exception:  # the message and `debug` stay; only the attributes are missing
        return err
    if isinstance(parsed, dict):
        err.details = parsed
        # The variants of the error and of its sources, outermost first.
        variants, node = [], parsed
        while isinstance(node, dict) and "variant" in node:
            variants.append(node["variant"])
            node = next((v for v in node.values() if isinstance(v, dict) and "variant" in v), None)
        err.variants = variants
        fields: dict[str, Any] = {}
        _flatten(parsed, fields)
        for k, v in fields.items():
            if not hasattr(err, k):
                try:
                    setattr(err, k, v)
                except AttributeError:
                    pass
    return err


def _call(fn: Callable, *args: Any, **kwargs: Any) -> Any:
    try:
        return fn(*args, **kwargs)
    except (JbearingError, ValueError) as e:
        _enrich(e)
        raise


# ---------------------------------------------------------------------------------------------
# Progress.


def _progress(progress: Any) -> Callable[[dict], None] | None:
    """A callable, None, or True for a tqdm bar over the steps of each cycle."""
    if progress is None or progress is False:
        return None
    if callable(progress):
        return progress
    if progress is True:
        from tqdm.auto import tqdm

        bar: dict[str, Any] = {}

        def show(ev: dict) -> None:
            # One bar per method over all its time steps; the cycle and the step's residual
            # beside it (the number of cycles is not known in advance).
            e = ev["event"]
            if e == "method_started":
                bar["bar"] = tqdm(desc=ev["method"], unit="step")
                bar["last"] = (None, 0)
            elif e == "step" and "bar" in bar:
                cycle, done = bar["last"]
                bar["bar"].update(ev["step"] - done if cycle == ev["cycle"] else ev["step"])
                bar["last"] = (ev["cycle"], ev["step"])
                bar["bar"].set_postfix(cycle=ev["cycle"], residual=f"{ev['residual']:.1e}")
            elif e == "cycle" and "bar" in bar:
                bar["bar"].set_postfix(cycle=ev["cycle"], change=f"{ev['residual']:.1e}")
            elif e == "method_done" and "bar" in bar:
                bar.pop("bar").close()
            elif e == "warning":
                print(f"warning: {ev['message']}")

        return show
    raise TypeError("progress must be None, True (tqdm) or a callable taking a dict")


# ---------------------------------------------------------------------------------------------
# Report -> DataTree, the layout of CASE.h5 (jbearing::output::hdf5).


def _f8(buf: bytes) -> np.ndarray:
    return np.frombuffer(buf, dtype="<f8").copy()


# The names, units, long names and descriptions the HDF5 writer uses (jbearing::output::layout).
_LAYOUT = _jbearing.layout()
_TEXT = _LAYOUT["texts"]


def _var(name: str, dim: str | tuple | None, values: Any, **extra: Any) -> tuple:
    """(dims, values, attrs) of the layout table's variable ``name`` for an xarray Dataset."""
    units, long = _LAYOUT["variables"][name]
    attrs = {"units": units, "long_name": long} if units else {"long_name": long}
    return (() if dim is None else dim, values, {**attrs, **extra})


def _method_dataset(m: dict) -> tuple[xr.Dataset, xr.Dataset | None]:
    crank = _f8(m["crank_angle"])
    coords = {
        "crank_angle": _var("crank_angle", "crank_angle", crank),
        "time": _var("time", "crank_angle", _f8(m["time"])),
    }
    data = {
        name: ("crank_angle", _f8(v), {"units": units, "long_name": long})
        for name, long, units, v in m["series"]
    }
    attrs: dict[str, Any] = {"method": m["method"], "description": m["description"]}
    for k, v in m["solver_info"]:
        attrs[k] = np.int8(v) if isinstance(v, bool) else v
    ds = xr.Dataset(data, coords=coords, attrs=attrs)
    f = m.get("fields")
    if f is None:
        return ds, None
    fc = {
        "field_crank_angle": _var("field_crank_angle", "field_crank_angle", _f8(f["crank_angle"])),
        "field_time": _var("field_time", "field_crank_angle", _f8(f["time"])),
        "theta": _var("theta", "theta", _f8(f["theta"]), axis="X"),
        "z": _var("z", "z", _f8(f["z"]), axis="Y"),
    }
    fd = {
        name: (
            ("field_crank_angle", "theta", "z"),
            _f8(buf).reshape(shape),
            {"units": units, "long_name": long},
        )
        for name, long, units, buf, shape in f["fields"]
    }
    fields = xr.Dataset(fd, coords=fc, attrs={"description": _TEXT["fields_description"]})
    return ds, fields


def _closed_form_dataset(t: dict) -> xr.Dataset:
    rows = t["rows"]
    models = np.array([r[0] for r in rows], dtype=object)
    data: dict[str, Any] = {
        "status": _var("status", "model", np.array([r[1] for r in rows], dtype=object))
    }
    if rows:
        for k, (name, _, units, long) in enumerate(rows[0][2]):
            data[name] = (
                "model",
                np.array([r[2][k][1] for r in rows], dtype="f8"),
                {"units": units, "long_name": long},
            )
    return xr.Dataset(
        data,
        coords={"model": _var("model", "model", models)},
        attrs={
            "description": _TEXT["closed_form_description"],
            "load_basis": t["load_basis"],
            "load_x": t["load"][0],
            "load_y": t["load"][1],
            "relative_speed": t["relative_speed"],
        },
    )


def _report_tree(r: dict) -> xr.DataTree:
    run = r["run"]
    radius, length, clearance = r["geometry"]
    attrs: dict[str, Any] = {
        "title": f"jbearing results for case '{r['case_name']}'",
        "Conventions": _TEXT["conventions"],
        "source": f"jbearing {run['jbearing_version']} (commit {run['git_commit']})",
        "history": f"{run['started_utc']} jbearing run of case '{r['case_name']}'",
        "case_name": r["case_name"],
        "case_text": r["case_text"],
        "case_path": r["case_path"],
        "jbearing_version": run["jbearing_version"],
        "git_commit": run["git_commit"],
        "wall_time_s": run["wall_time"],
        "started_utc": run["started_utc"],
        "methods": " ".join(m["method"] for m in r["methods"]),
        "warning_count": len(r["warnings"]),
    }
    if r["warnings"]:
        attrs["warnings"] = [w[1] for w in r["warnings"]]
        attrs["warning_kinds"] = [w[0] for w in r["warnings"]]
    root = xr.Dataset(
        {
            "radius": _var("radius", None, radius),
            "length": _var("length", None, length),
            "radial_clearance": _var("radial_clearance", None, clearance),
        },
        attrs=attrs,
    )
    params: dict[str, Any] = {}
    for key, value, units, long, kind in r["parameters"]:
        a: dict[str, Any] = {"long_name": long}
        if units:
            a["units"] = units
        if kind == "flag":
            value = np.int8(value)
            a["flag_values"] = np.array([0, 1], dtype="i1")
            a["flag_meanings"] = "false true"
        elif kind == "integer":
            value = np.int64(value)
        elif kind == "text":
            value = np.array(value, dtype=object)
        params[key] = ((), value, a)
    tree: dict[str, xr.Dataset] = {
        "/": root,
        "parameters": xr.Dataset(params, attrs={"description": _TEXT["parameters_description"]}),
    }
    for m in r["methods"]:
        ds, fields = _method_dataset(m)
        tree[m["method"]] = ds
        if fields is not None:
            tree[f"{m['method']}/fields"] = fields
    tree["summary"] = xr.Dataset(
        {
            name: ("solution_method", np.array(values, dtype="f8"), {"units": units, "long_name": long})
            for name, long, units, values in r["summary"]
        },
        coords={
            "solution_method": _var(
                "solution_method", "solution_method", np.array(r["method_names"], dtype=object)
            )
        },
        attrs={"description": _TEXT["summary_description"]},
    )
    if r["closed_form"] is not None:
        tree["closed_form"] = _closed_form_dataset(r["closed_form"])
    if r["input_files"]:
        tree["input_files"] = xr.Dataset(
            {"text": _var("text", "file", np.array([f[1] for f in r["input_files"]], dtype=object))},
            coords={
                "file": _var("file", "file", np.array([f[0] for f in r["input_files"]], dtype=object))
            },
            attrs={"description": _TEXT["input_files_description"]},
        )
    return xr.DataTree.from_dict(tree)


# ---------------------------------------------------------------------------------------------
# Case files.


def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, (float, np.floating)):
        x = float(v)
        if math.isnan(x):
            return "nan"
        if math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return repr(x)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, np.ndarray):
        v = v.tolist()
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(f"cannot write {type(v).__name__} {v!r} into a case file")


def case_toml(case: Mapping[str, Any]) -> str:
    """A case file's TOML text from a dict of its tables (``cases/README.md`` lists the keys):
    top-level scalars first, then ``[table]`` per dict and ``[[table]]`` per list of dicts."""
    lines: list[str] = []
    for k, v in case.items():
        if not isinstance(v, Mapping) and not (
            isinstance(v, list) and v and all(isinstance(x, Mapping) for x in v)
        ):
            lines.append(f"{k} = {_toml_value(v)}")
    for k, v in case.items():
        if isinstance(v, Mapping):
            lines.append(f"\n[{k}]")
            sub = [(kk, vv) for kk, vv in v.items() if isinstance(vv, Mapping)]
            for kk, vv in v.items():
                if not isinstance(vv, Mapping):
                    lines.append(f"{kk} = {_toml_value(vv)}")
            for kk, vv in sub:
                lines.append(f"\n[{k}.{kk}]")
                for k3, v3 in vv.items():
                    lines.append(f"{k3} = {_toml_value(v3)}")
        elif isinstance(v, list) and v and all(isinstance(x, Mapping) for x in v):
            for item in v:
                lines.append(f"\n[[{k}]]")
                for kk, vv in item.items():
                    lines.append(f"{kk} = {_toml_value(vv)}")
    return "\n".join(lines) + "\n"


def _rpm(omega: float) -> float:
    return float(omega) * 60.0 / (2.0 * math.pi)


def _merge(base: dict, extra: Mapping[str, Any] | None) -> dict:
    for k, v in (extra or {}).items():
        if isinstance(v, Mapping) and isinstance(base.get(k), dict):
            _merge(base[k], v)
        else:
            base[k] = v
    return base


def _cycle_case(
    *,
    name: str,
    crank_angle: Iterable[float],
    load_x: Iterable[float],
    load_y: Iterable[float],
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
    crank_speed: float,
    journal_speed: float | None,
    bearing_speed: float,
    cycle: float,
    grooves: Iterable[Mapping[str, float]] | None,
    feed_pressure: float | None,
    grid: tuple[int, int] | None,
    steps_per_cycle: int | None,
    max_cycles: int | None,
    initial_eccentricity: tuple[float, float] | None,
    rigorous: bool,
    mobility: bool,
    options: Mapping[str, Any] | None,
) -> dict:
    angles = np.asarray(crank_angle, dtype="f8").ravel()
    lx = np.broadcast_to(np.asarray(load_x, dtype="f8"), angles.shape)
    ly = np.broadcast_to(np.asarray(load_y, dtype="f8"), angles.shape)
    case: dict[str, Any] = {
        "version": 1,
        "name": name,
        "description": "written by the jbearing Python package",
        "bearing": {"radius_m": radius, "length_m": length, "radial_clearance_m": clearance},
        "lubricant": {"viscosity_pa_s": viscosity},
        "operation": {
            "cycle_deg": cycle,
            "crank_speed_rpm": _rpm(crank_speed),
            "journal_speed_rpm": _rpm(crank_speed if journal_speed is None else journal_speed),
            "bearing_speed_rpm": _rpm(bearing_speed),
        },
        "load": {"crank_angle_deg": angles, "x_n": lx, "y_n": ly},
        "methods": {"rigorous": rigorous, "mobility": mobility},
        "output": {"plots": False},
    }
    if grooves:
        # Groove: center_angle [rad], circumferential_length [m], axial_width [m], axial_center [m].
        case["grooves"] = [
            {
                "center_angle_deg": math.degrees(g["center_angle"]),
                "axial_center_m": g.get("axial_center", 0.0),
                "circumferential_length_m": g["circumferential_length"],
                "axial_width_m": g["axial_width"],
            }
            for g in grooves
        ]
    if feed_pressure is not None:
        case["feed"] = {"pressure_pa": feed_pressure}
    if grid is not None:
        case["grid"] = {"n_theta": int(grid[0]), "n_z": int(grid[1])}
    solver: dict[str, Any] = {}
    if steps_per_cycle is not None:
        solver["time_steps_per_cycle"] = int(steps_per_cycle)
    if max_cycles is not None:
        solver["max_cycles"] = int(max_cycles)
    if initial_eccentricity is not None:
        solver["initial_eccentricity"] = [float(x) for x in initial_eccentricity]
    if solver:
        case["solver"] = solver
    return _merge(case, options)


def _case_path(name: str, base_dir: str | os.PathLike | None) -> Path:
    return Path(base_dir if base_dir is not None else os.getcwd()) / f"{name}.toml"


# ---------------------------------------------------------------------------------------------
# Public functions.


def run_case(
    path: str | os.PathLike,
    *,
    out_dir: str | os.PathLike | None = None,
    progress: Any = None,
    max_memory_gib: float = 8.0,
    max_hours: float = 24.0,
) -> xr.DataTree:
    """Run the TOML case file at ``path`` as ``jbearing run`` does and return its results as a
    DataTree with the groups, names, units and dimensions of ``CASE.h5``. With ``out_dir``, the
    CLI's files are written there as well. Cases above the memory / time limits are refused
    (:class:`BudgetError`), as by the CLI's ``--max-memory-gb`` / ``--max-hours``."""
    r = _call(
        _jbearing.run_case_file,
        os.fspath(path),
        out_dir=None if out_dir is None else os.fspath(out_dir),
        progress=_progress(progress),
        max_memory_gib=max_memory_gib,
        max_hours=max_hours,
    )
    return _report_tree(r)


def solve_case_text(
    text: str,
    *,
    name: str = "python_case",
    base_dir: str | os.PathLike | None = None,
    out_dir: str | os.PathLike | None = None,
    progress: Any = None,
    max_memory_gib: float = 8.0,
    max_hours: float = 24.0,
) -> xr.DataTree:
    """:func:`run_case` for a case file's TOML text; relative CSV paths are taken from
    ``base_dir`` (default: the working directory), where the case is said to be ``NAME.toml``."""
    r = _call(
        _jbearing.solve_case_text,
        text,
        os.fspath(_case_path(name, base_dir)),
        out_dir=None if out_dir is None else os.fspath(out_dir),
        progress=_progress(progress),
        max_memory_gib=max_memory_gib,
        max_hours=max_hours,
    )
    return _report_tree(r)


_CYCLE_DOC = """
    Keyword arguments (SI units; crank angles in degrees, as in the result files):

    crank_angle, load_x, load_y : arrays
        The load on the journal in the bearing frame (N) at the crank angles of one cycle
        (degree; a periodic table, interpolated linearly). A scalar load broadcasts.
    radius, length, clearance : float
        Bearing radius R, length L and radial clearance c (m).
    viscosity : float
        Dynamic viscosity (Pa s).
    crank_speed : float
        Crank angular speed (rad/s); the cycle lasts cycle / crank_speed.
    journal_speed, bearing_speed : float
        Journal and bearing angular speeds (rad/s); journal_speed defaults to crank_speed.
    cycle : float
        Cycle length in crank degrees (360 or 720).
    grooves : list of dicts
        Feed grooves: center_angle (rad), circumferential_length (m), axial_width (m),
        axial_center (m, default 0). The JFO film needs an oil supply: a groove with
        feed_pressure (Pa).
    grid : (n_theta, n_z)
        Finite-volume grid of the film (default: the library's validated grid of this L/D,
        120 x 31, or 160 x 23 below L/D = 1/4).
    steps_per_cycle, max_cycles, initial_eccentricity
        Solver settings ([solver] of the case file).
    options : dict
        Further case-file tables or keys, merged into the generated case (see cases/README.md).
    name, base_dir, out_dir, progress, max_memory_gib, max_hours
        As for :func:`solve_case_text`.

    Returns the DataTree of :func:`run_case`; its ``case_text`` attribute is the case file.
"""


def _cycle(rigorous: bool, mobility: bool, kw: dict) -> xr.DataTree:
    run_kw = {k: kw.pop(k) for k in ("base_dir", "out_dir", "progress", "max_memory_gib", "max_hours") if k in kw}
    case = _cycle_case(rigorous=rigorous, mobility=mobility, **kw)
    return solve_case_text(case_toml(case), name=kw["name"], **run_kw)


def inverse_cycle(
    *,
    crank_angle,
    load_x,
    load_y,
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
    crank_speed: float,
    journal_speed: float | None = None,
    bearing_speed: float = 0.0,
    cycle: float = 360.0,
    grooves=None,
    feed_pressure: float | None = None,
    grid: tuple[int, int] | None = None,
    steps_per_cycle: int | None = None,
    max_cycles: int | None = None,
    initial_eccentricity: tuple[float, float] | None = None,
    options: Mapping[str, Any] | None = None,
    name: str = "inverse_cycle",
    **run: Any,
) -> xr.DataTree:
    """The periodic journal orbit under a load history by the rigorous inverse solver (the
    mass-conserving finite-difference film), as the ``rigorous`` group of ``CASE.h5``."""
    kw = {k: v for k, v in locals().items() if k != "run"}
    return _cycle(True, False, {**kw, **run})


def mobility_cycle(
    *,
    crank_angle,
    load_x,
    load_y,
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
    crank_speed: float,
    journal_speed: float | None = None,
    bearing_speed: float = 0.0,
    cycle: float = 360.0,
    grooves=None,
    feed_pressure: float | None = None,
    grid: tuple[int, int] | None = None,
    steps_per_cycle: int | None = None,
    max_cycles: int | None = None,
    initial_eccentricity: tuple[float, float] | None = None,
    options: Mapping[str, Any] | None = None,
    name: str = "mobility_cycle",
    **run: Any,
) -> xr.DataTree:
    """The periodic journal orbit under a load history by Booker's mobility method, as the
    ``mobility`` group of ``CASE.h5``."""
    kw = {k: v for k, v in locals().items() if k != "run"}
    return _cycle(False, True, {**kw, **run})


inverse_cycle.__doc__ += _CYCLE_DOC
mobility_cycle.__doc__ += _CYCLE_DOC


def closed_form(
    *,
    load_x: float,
    load_y: float,
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
    journal_speed: float,
    bearing_speed: float = 0.0,
    models: str | Iterable[str] = "all",
) -> xr.Dataset:
    """Static equilibrium of the closed-form film models ([Flores2009], [Flores2006]) under the
    constant load (load_x, load_y) (N) at relative speed journal_speed - bearing_speed (rad/s):
    the ``closed_form`` group of ``CASE.h5`` (dimension ``model``; eccentricity_ratio,
    attitude_angle, min_film_thickness, film forces, sommerfeld_number, status)."""
    case = {
        "version": 1,
        "name": "closed_form",
        "bearing": {"radius_m": radius, "length_m": length, "radial_clearance_m": clearance},
        "lubricant": {"viscosity_pa_s": viscosity},
        "operation": {
            "cycle_deg": 360.0,
            "crank_speed_rpm": _rpm(journal_speed),
            "journal_speed_rpm": _rpm(journal_speed),
            "bearing_speed_rpm": _rpm(bearing_speed),
        },
        "load": {"crank_angle_deg": [0.0], "x_n": [float(load_x)], "y_n": [float(load_y)]},
        "methods": {"rigorous": False, "mobility": True, "closed_form": True},
        "closed_form": {"models": models if isinstance(models, str) else list(models)},
    }
    t = _call(
        _jbearing.closed_form_text, case_toml(case), os.fspath(_case_path("closed_form", None))
    )
    return _closed_form_dataset(t)


def steady(
    *,
    load_x: float,
    load_y: float,
    radius: float,
    length: float,
    clearance: float,
    viscosity: float,
    journal_speed: float,
    bearing_speed: float = 0.0,
    grid: tuple[int, int] | None = None,
    grooves=None,
    feed_pressure: float = 0.0,
    bulk_modulus: float = 1.5e9,
    cavitation_pressure: float = 0.0,
    ambient_pressure: float = 0.0,
) -> xr.Dataset:
    """The steady mass-conserving (JFO) film of a rigid bearing under the constant load
    (load_x, load_y) on the journal (N): Newton on the eccentricity until the film force
    balances the load (|F + W| <= 1e-8 |W|).

    Grooves (dicts: center_angle [rad], circumferential_length [m], axial_width [m],
    axial_center [m]) are fed at feed_pressure (Pa); without grooves the film is fed along the
    axial line at the widest gap. grid = (n_theta, n_z) defaults to the library's validated
    grid of this L/D (120 x 31, or 160 x 23 below L/D = 1/4). Returns a Dataset on (theta, z) with the fields pressure,
    film_thickness, film_content and the scalars named as the series of ``CASE.h5``
    (eccentricity_x/y, eccentricity_ratio, attitude_angle, min_film_thickness, max_pressure,
    side_leakage, supply_flow, power_loss, cavitated_fraction) and the film force."""
    g = [
        (
            float(gr["center_angle"]),
            float(gr.get("axial_center", 0.0)),
            float(gr["circumferential_length"]) / float(radius),
            float(gr["axial_width"]),
        )
        for gr in (grooves or [])
    ]
    r = _call(
        _jbearing.steady,
        radius=float(radius),
        length=float(length),
        clearance=float(clearance),
        viscosity=float(viscosity),
        load_x=float(load_x),
        load_y=float(load_y),
        journal_speed=float(journal_speed),
        bearing_speed=float(bearing_speed),
        n_theta=None if grid is None else int(grid[0]),
        n_z=None if grid is None else int(grid[1]),
        grooves=g,
        feed_pressure=float(feed_pressure),
        bulk_modulus=float(bulk_modulus),
        cavitation_pressure=float(cavitation_pressure),
        ambient_pressure=float(ambient_pressure),
        supply_line=not g,
    )
    shape = tuple(r["shape"])
    ex, ey = r["eccentricity_ratio"]
    c = float(clearance)

    def field(key: str, units: str, long: str):
        return (("theta", "z"), _f8(r[key]).reshape(shape), {"units": units, "long_name": long})

    def scalar(v: float, units: str, long: str):
        return ((), float(v), {"units": units, "long_name": long})

    data = {
        "pressure": field("pressure", "Pa", "film pressure, gauge"),
        "film_thickness": field("film_thickness", "m", "film thickness"),
        "film_content": field("film_content", "1", "film content (density ratio / film fraction)"),
        "load_x": scalar(load_x, "N", "load on the journal, x"),
        "load_y": scalar(load_y, "N", "load on the journal, y"),
        "eccentricity_x": scalar(c * ex, "m", "journal centre, x"),
        "eccentricity_y": scalar(c * ey, "m", "journal centre, y"),
        "eccentricity_ratio": scalar(math.hypot(ex, ey), "1", "eccentricity ratio"),
        "attitude_angle": scalar(
            math.atan2(ey, ex), "rad", "attitude angle of the journal centre, from +x towards +y"
        ),
        "load_attitude_angle": scalar(
            r["attitude_angle"],
            "rad",
            "angle from the load to the eccentricity, positive in the direction of rotation",
        ),
        "min_film_thickness": scalar(r["min_film_thickness"], "m", "minimum film thickness"),
        "max_pressure": scalar(r["max_pressure"], "Pa", "peak film pressure"),
        "cavitated_fraction": scalar(
            r["cavitated_fraction"], "1", "cavitated fraction of the film area"
        ),
        "side_leakage": scalar(r["side_leakage"], "m3 s-1", "side leakage, both ends"),
        "supply_flow": scalar(r["supply_flow"], "m3 s-1", "supply flow, all grooves (or the supply line)"),
        "power_loss": scalar(r["power_loss"], "W", "power loss"),
        "film_force_x": scalar(r["film_force"][0], "N", "film force on the journal, x"),
        "film_force_y": scalar(r["film_force"][1], "N", "film force on the journal, y"),
        "friction_torque_journal": scalar(
            r["friction_torque_journal"], "N m", "film torque on the journal about +z"
        ),
    }
    coords = {
        "theta": _var("theta", "theta", _f8(r["theta"]), axis="X"),
        "z": _var("z", "z", _f8(r["z"]), axis="Y"),
    }
    return xr.Dataset(
        data,
        coords=coords,
        attrs={
            "description": "steady mass-conserving (JFO) film under a constant load "
            "(jbearing_solvers::reynolds, Newton on the eccentricity)",
            "newton_iterations": int(r["newton_iterations"]),
            "force_residual": float(r["force_residual"]),
            "film_solves": int(r["film_solves"]),
        },
    )
