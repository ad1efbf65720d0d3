"""The jbearing Python package against the CLI's HDF5 files, and against closed forms.

Equality tests: the same case through ``jbearing run`` (the binary) and through the package
(``run_case``, ``mobility_cycle``) goes through the same Rust functions (``solve_case_checked``),
so the numbers must agree to round-off: 1e-12 relative (the solves are deterministic; the margin
only allows for a different optimisation of the same code in the two builds).

Physics tests: the steady finite-difference film at L/D = 1/16 against the short-bearing (Gumbel)
closed form, and the inverse solver under a constant load against the steady solve.
"""

from __future__ import annotations

import math
import threading
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import jbearing as jb
from conftest import CASES

# Same code path in both builds (see the module docstring).
RTOL = 1e-12

# Attributes that differ between two runs of the same case by nature (wall time, start time),
# or name the build (the binary and the extension are separate builds of one tree).
RUN_ATTRS = {"wall_time_s", "started_utc", "history", "source", "git_commit"}


def assert_same_values(a: xr.DataArray, b: xr.DataArray, where: str) -> None:
    va, vb = np.asarray(a.values), np.asarray(b.values)
    assert va.shape == vb.shape, f"{where}: shape {va.shape} != {vb.shape}"
    if va.dtype.kind in "fc" or vb.dtype.kind in "fc":
        va, vb = va.astype("f8"), vb.astype("f8")
        assert np.array_equal(np.isnan(va), np.isnan(vb)), f"{where}: NaNs differ"
        ok = ~np.isnan(va)
        np.testing.assert_allclose(va[ok], vb[ok], rtol=RTOL, atol=0, err_msg=where)
    else:
        assert [str(x) for x in va.ravel()] == [str(x) for x in vb.ravel()], where


def assert_same_attrs(a: dict, b: dict, where: str, skip=()) -> None:
    keys_a = set(a) - set(skip)
    keys_b = set(b) - set(skip)
    assert keys_a == keys_b, f"{where}: attributes {sorted(keys_a ^ keys_b)} differ"
    for k in keys_a:
        x, y = a[k], b[k]
        if isinstance(x, (float, np.floating)) or isinstance(y, (float, np.floating)):
            assert float(x) == pytest.approx(float(y), rel=RTOL, nan_ok=True), f"{where}.{k}"
        else:
            assert np.array_equal(np.asarray(x), np.asarray(y)), f"{where}.{k}: {x!r} != {y!r}"


def assert_same_dataset(py: xr.Dataset, h5: xr.Dataset, group: str) -> None:
    """Same variables and coordinates with the same dimensions, units, long names, values."""
    assert set(py.variables) == set(h5.variables), (
        f"{group}: variables {sorted(set(py.variables) ^ set(h5.variables))} differ"
    )
    assert set(py.coords) == set(h5.coords), f"{group}: coordinates differ"
    for name in h5.variables:
        a, b = py[name], h5[name]
        where = f"{group}/{name}"
        assert a.dims == b.dims, f"{where}: dims {a.dims} != {b.dims}"
        assert_same_attrs(a.attrs, b.attrs, where)
        assert_same_values(a, b, where)
    assert_same_attrs(py.attrs, h5.attrs, group, skip=RUN_ATTRS)


def compare_tree_with_file(tree: xr.DataTree, h5: Path, groups: list[str]) -> None:
    for group in groups:
        with xr.open_dataset(h5, engine="h5netcdf", group=None if group == "/" else group) as f:
            file_ds = f.load()
        node = tree if group == "/" else tree[group]
        assert_same_dataset(node.to_dataset(inherit=False), file_ds, group)
    # No group in the tree that the file lacks (the file's VTKHDF surface is for pyvista).
    tree_groups = {n.path.lstrip("/") or "/" for n in tree.subtree}
    assert tree_groups == set(groups), f"tree groups {sorted(tree_groups)}"


@pytest.fixture(scope="module")
def small_cli(tmp_path_factory, run_cli) -> Path:
    out = tmp_path_factory.mktemp("cli")
    run_cli("run", CASES / "small.toml", "--out", out, "--no-progress")
    return out / "small.h5"


def test_run_case_gives_the_cli_file(small_cli):
    events = []
    tree = jb.run_case(CASES / "small.toml", progress=events.append)
    groups = [
        "/",
        "parameters",
        "rigorous",
        "rigorous/fields",
        "mobility",
        "summary",
        "closed_form",
        "input_files",
    ]
    compare_tree_with_file(tree, small_cli, groups)
    # Progress reached the callable: steps of the rigorous method's cycles (72 steps each after
    # the run-in, cycle 0), the end of each cycle, and both methods' start and end.
    kinds = {e["event"] for e in events}
    assert {"method_started", "step", "cycle", "method_done"} <= kinds, kinds
    steps = [e for e in events if e["event"] == "step" and e["method"] == "rigorous"]
    assert steps and all(e["steps"] == 72 for e in steps if e["cycle"] >= 1)
    cycles = [e for e in events if e["event"] == "cycle" and e["method"] == "rigorous"]
    n_cycles = int(tree["rigorous"].attrs["cycles"])
    assert [e["cycle"] for e in cycles] == list(range(1, n_cycles + 1))
    assert {e["cycle"] for e in steps} == set(range(0, n_cycles + 1))
    # The summary and the series in the tree are the file's units: h_min in m, about c/4 here.
    h = tree["summary"]["min_film_thickness_min"].sel(solution_method="rigorous")
    assert tree["summary"]["min_film_thickness_min"].attrs["units"] == "m"
    assert 1e-6 < float(h) < 4e-5


def test_mobility_cycle_keywords_give_the_cli_result_of_its_case_text(tmp_path, run_cli):
    """Keyword arguments -> case text -> the same numbers as ``jbearing run`` of that text."""
    angles = np.arange(0.0, 360.0, 30.0)
    load_x = -1500.0 - 500.0 * np.cos(np.radians(angles))
    load_y = 500.0 * np.sin(np.radians(angles))
    tree = jb.mobility_cycle(
        crank_angle=angles,
        load_x=load_x,
        load_y=load_y,
        radius=0.025,
        length=0.02,
        clearance=4e-5,
        viscosity=0.02,
        crank_speed=1800 * 2 * math.pi / 60,
        options={"output": {"samples_per_cycle": 72}},
        name="kw_mobility",
        base_dir=tmp_path,
    )
    assert "rigorous" not in tree.children and "mobility" in tree.children
    mob = tree["mobility"]
    assert mob.sizes["crank_angle"] == 72
    assert mob["eccentricity_x"].attrs["units"] == "m"
    # The load went in as given: the stored load at the table's points is the table.
    at = mob["load_x"].sel(crank_angle=angles)
    np.testing.assert_allclose(at.values, load_x, rtol=1e-12)
    case = tmp_path / "kw_mobility.toml"
    case.write_text(tree.attrs["case_text"])
    run_cli("run", case, "--out", tmp_path, "--no-progress")
    compare_tree_with_file(
        tree, tmp_path / "kw_mobility.h5", ["/", "parameters", "mobility", "summary"]
    )


def test_steady_film_tends_to_the_short_bearing_closed_form():
    """At L/D = 1/16 the finite-difference film (JFO, fed at the widest gap) and the
    short-bearing Gumbel film agree: validation/tests/closed_form_vs_reynolds.rs finds the
    force at fixed eccentricity within 1 % and its direction within 0.1 deg on this grid
    (180 x 22) at this L/D. Under the same load the equilibria then agree to about that: the
    short-bearing force grows like eps / (1 - eps^2)^2, d ln F / d ln eps >= 1, so 1 % in force
    is at most 1 % in eps; the tolerances below are that 1 % and 0.5 deg."""
    R, C, MU, omega = 0.02, 40e-6, 0.02, 100.0
    L = 2 * R / 16
    bearing = dict(radius=R, length=L, clearance=C, viscosity=MU, journal_speed=omega)
    # About 0.3 N puts the short-bearing equilibrium near eps = 0.5 (mu U L^3 / (4 c^2) ~ 0.1 N).
    load = (0.0, -0.3)
    cf = jb.closed_form(load_x=load[0], load_y=load[1], models=["short_gumbel"], **bearing)
    st = jb.steady(load_x=load[0], load_y=load[1], grid=(180, 22), **bearing)
    eps_cf = float(cf.eccentricity_ratio.sel(model="short_gumbel"))
    assert 0.3 < eps_cf < 0.8, eps_cf  # a mid-range equilibrium, not a trivial one
    eps_fd = float(st.eccentricity_ratio)
    assert eps_fd == pytest.approx(eps_cf, rel=0.01)
    # Line of centres: the closed form's angle from +x, the FD journal centre's.
    gamma_cf = float(cf.line_of_centres_angle.sel(model="short_gumbel"))
    gamma_fd = float(st.attitude_angle)
    d = math.remainder(gamma_fd - gamma_cf, 2 * math.pi)
    assert abs(math.degrees(d)) < 0.5, math.degrees(d)
    # The film carries the load (Newton's own criterion, 1e-8 |W|), and the dataset is on the grid.
    assert st.film_force_x.item() + load[0] == pytest.approx(0.0, abs=1e-7 * 0.3)
    assert st.film_force_y.item() + load[1] == pytest.approx(0.0, abs=1e-7 * 0.3)
    assert st.pressure.dims == ("theta", "z") and st.pressure.shape == (180, 22)
    assert st.pressure.attrs["units"] == "Pa"
    assert float(st.min_film_thickness) == pytest.approx(C * (1 - eps_fd), rel=1e-9)


def test_inverse_cycle_under_a_constant_load_settles_at_the_steady_solution(capsys):
    """The inverse (time-stepping) solver under a constant load ends at rest where the steady
    Newton solve puts the journal: the same film, two independent ways to its equilibrium.
    The journal starts at the bearing centre. Tolerance 1e-3 in eps: the run stops when a
    cycle moves eps by less than the periodicity tolerance 1e-4; a journal contracting towards
    its fixed point by a factor rho per cycle is then within 1e-4 rho / (1 - rho) of it, below
    1e-3 for rho < 0.9."""
    groove = dict(center_angle=math.pi / 2, circumferential_length=0.006, axial_width=0.006)
    bearing = dict(radius=0.025, length=0.02, clearance=4e-5, viscosity=0.02)
    omega = 1800 * 2 * math.pi / 60
    load = (-1500.0, 0.0)
    st = jb.steady(
        load_x=load[0], load_y=load[1], journal_speed=omega, grid=(48, 8),
        grooves=[groove], feed_pressure=2e5, **bearing,
    )
    tree = jb.inverse_cycle(
        crank_angle=[0.0], load_x=[load[0]], load_y=[load[1]], crank_speed=omega,
        grooves=[groove], feed_pressure=2e5, grid=(48, 8), steps_per_cycle=36, max_cycles=20,
        options={"output": {"samples_per_cycle": 36, "field_snapshots": 4}},
        name="kw_inverse", progress=True, **bearing,
    )
    # progress=True: a tqdm bar for the method, with the cycle and the step residual.
    bar = capsys.readouterr().err
    assert "rigorous" in bar and "cycle=" in bar and "residual=" in bar, bar
    rig = tree["rigorous"]
    assert rig.attrs["periodic"] == 1
    ex = rig["eccentricity_x"].values / 4e-5
    ey = rig["eccentricity_y"].values / 4e-5
    assert np.max(np.abs(ex - float(st.eccentricity_x) / 4e-5)) < 1e-3
    assert np.max(np.abs(ey - float(st.eccentricity_y) / 4e-5)) < 1e-3
    fields = tree["rigorous/fields"]
    assert fields["pressure"].dims == ("field_crank_angle", "theta", "z")
    assert fields.sizes["theta"] == 48 and fields.sizes["z"] == 8


def test_errors_carry_the_numbers():
    # A case-file error names the key and the line of the generated case text.
    with pytest.raises(jb.CaseError) as e:
        jb.mobility_cycle(
            crank_angle=[0.0], load_x=[-100.0], load_y=[0.0], radius=0.025, length=0.02,
            clearance=-4e-5, viscosity=0.02, crank_speed=100.0,
        )
    err = e.value
    assert err.kind == "Key" and err.key == "bearing.radial_clearance_m"
    assert isinstance(err.line, int) and err.line > 1
    assert "radial_clearance_m" in str(err)
    # A missing case file: the Read variant, its file, and the OS error below it (errno 2).
    with pytest.raises(jb.CaseError) as e:
        jb.run_case(CASES / "no_such_case.toml")
    err = e.value
    assert err.kind == "Read" and err.file == str(CASES / "no_such_case.toml")
    assert err.source_variant == "Os" and err.code == 2, err.details
    # A load far above what the film can carry at the solver's largest eccentricity: the
    # steady Newton solve stops, and the error carries its iteration count, residual and place.
    load = 5e6
    with pytest.raises(jb.SolverError) as e:
        jb.steady(load_x=0.0, load_y=-load, radius=0.025, length=0.02, clearance=4e-5,
                  viscosity=0.02, journal_speed=100.0, grid=(48, 8))
    err = e.value
    assert err.kind == "SteadyLoadNotConverged", err.details
    assert isinstance(err.iterations, int) and err.iterations >= 1
    # The film's force at |eps| < 1 is a small part of 5 MN here: most of the load is left.
    assert 0.5 * load < err.force_residual <= load
    ex, ey = err.eccentricity_ratio
    # Pushed to the solver's bound |eps| <= 0.995: the clamp rescales (ex, ey) to that length in
    # floating point, so hypot may land a few units in the last place above it.
    assert 0.9 < math.hypot(ex, ey) <= 0.995 * (1.0 + 4.0 * 2.2e-16)
    # The attributes are the message's numbers (shortest round-trip forms in both languages).
    assert f"after {err.iterations} Newton" in str(err) and repr(ey) in str(err)
    # A parameter the Reynolds solver refuses: a ValueError carrying name and value.
    with pytest.raises(ValueError) as e:
        jb.steady(load_x=0.0, load_y=0.0, radius=0.02, length=0.01, clearance=4e-5,
                  viscosity=0.02, journal_speed=100.0)
    assert e.value.kind == "InvalidParameter" and e.value.name == "load" and e.value.value == 0.0


def test_solves_release_the_gil():
    """A Python thread keeps running while a solve is under way in another."""
    ticks = 0
    done = threading.Event()

    def count():
        nonlocal ticks
        while not done.is_set():
            ticks += 1
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    start = time.perf_counter()
    ticks_before = ticks
    jb.steady(load_x=0.0, load_y=-20.0, radius=0.02, length=0.0025, clearance=40e-6,
              viscosity=0.02, journal_speed=100.0, grid=(180, 22))
    elapsed = time.perf_counter() - start
    done.set()
    t.join()
    # Held GIL: the counter would not move during the solve. At ~1 ms per tick, a released GIL
    # gives a tick count of the order of the solve's milliseconds; ask for a tenth of it.
    assert elapsed > 0.05, "solve too short to tell"
    assert ticks - ticks_before > 0.1 * elapsed / 0.001, (ticks - ticks_before, elapsed)


# The compressor-like bearing of the inverse tests, for the interruption and error tests below.
_BEARING = dict(
    radius=0.025, length=0.02, clearance=4e-5, viscosity=0.02, feed_pressure=2e5,
    grooves=[dict(center_angle=math.pi / 2, circumferential_length=0.006, axial_width=0.006)],
)
_OMEGA = 1800 * 2 * math.pi / 60


def test_ctrl_c_stops_a_running_solve():
    """SIGINT during a solve (the GIL released, no progress callable) raises KeyboardInterrupt
    within a step or two instead of after the run. The solve asked for is far longer than the
    wait: 400 cycles of 360 steps with a periodicity tolerance it cannot meet early (a
    rotating load), ~10^5 film steps, minutes of work."""
    import os
    import signal

    # Python keeps SIGINT ignored when it starts with it ignored (a job started in the
    # background by a non-interactive shell, as a CI runner may): then no KeyboardInterrupt can
    # come. The handler a terminal's Python has, for this test, whatever the launch.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    angles = np.arange(0.0, 360.0, 5.0)
    started = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            jb.inverse_cycle(
                crank_angle=angles, load_x=800.0 * np.cos(np.radians(angles)),
                load_y=800.0 * np.sin(np.radians(angles)), crank_speed=_OMEGA, grid=(48, 8),
                steps_per_cycle=360, max_cycles=400,
                options={"solver": {"periodicity_tolerance": 1e-300}}, **_BEARING,
            )
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    # 0.5 s to the signal, then at most one signal interval (50 ms) and one film step.
    assert time.monotonic() - started < 5.0


def test_a_progress_callable_that_raises_stops_the_solve():
    """An exception in the progress callable stops the rigorous method after the step it was
    raised in, and is the exception the caller sees."""

    class Enough(Exception):
        pass

    steps = []

    def progress(event):
        if event["event"] == "step":
            steps.append(event)
            raise Enough

    with pytest.raises(Enough):
        jb.inverse_cycle(
            crank_angle=[0.0], load_x=[-1500.0], load_y=[0.0], crank_speed=_OMEGA,
            grid=(48, 8), steps_per_cycle=36, max_cycles=400,
            options={"solver": {"periodicity_tolerance": 1e-300}}, progress=progress,
            **_BEARING,
        )
    assert len(steps) == 1


def test_a_load_the_film_cannot_carry_names_the_step_in_python():
    """The rigorous method's collapse error reaches Python with the solver's numbers: the crank
    angle and cycle of the step, the eccentricity and the minimum film thickness there, which
    agree with each other (h_min = c (1 - |eps|) for an aligned journal)."""
    with pytest.raises(jb.SolverError) as e:
        jb.inverse_cycle(
            crank_angle=[0.0, 120.0, 240.0], load_x=[-1e3, -5e6, -1e3], load_y=[0.0, 0.0, 0.0],
            crank_speed=_OMEGA, grid=(48, 8), steps_per_cycle=36, max_cycles=3, **_BEARING,
        )
    err = e.value
    assert err.kind == "Rigorous", err.details
    assert err.source_variant == "Inverse", err.details
    # The whole chain of variants, outermost first (RunError, RigorousError, InverseError).
    assert err.variants == ["Rigorous", "Inverse", "Collapse"], err.details
    assert isinstance(err.cycle, int) and 0.0 <= err.crank_angle_deg <= 360.0
    assert err.min_film_thickness == pytest.approx(4e-5 * (1.0 - err.eccentricity), rel=1e-9)
    assert f"{err.crank_angle_deg:.2f}°" in str(err)
