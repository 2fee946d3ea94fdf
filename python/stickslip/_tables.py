# SPDX-License-Identifier: BSD-3-Clause
"""The results as tables and files: to_columns(), to_dataframe(), to_npz()
and save(), added to every result class by the package.

One definition of each result's table (COLUMNS): the rows are the result's
points (one per bin, lag, time, recorded point or sweep point, or (time,
velocity) pair of the white-noise references; one row for a single
estimate), and an estimate NAME has the columns NAME, NAME_error (its
standard error), NAME_lo and NAME_hi, as in the CSV (a solved value: NAME
and NAME_error). to_dataframe() makes a pandas DataFrame of
it, to_npz() a NumPy .npz file with the result's provenance (meta) beside the
arrays, written as the CLI writes --output: atomically.
"""
import io as _io
import json as _json
import os as _os

import numpy as _np

from . import _core


def _estimate(cols, name, e):
    cols[name] = _np.atleast_1d(_np.asarray(e.value, dtype=float)).ravel()
    cols[name + "_error"] = _np.atleast_1d(_np.asarray(e.stderr, dtype=float)).ravel()
    cols[name + "_lo"] = _np.atleast_1d(_np.asarray(e.lo, dtype=float)).ravel()
    cols[name + "_hi"] = _np.atleast_1d(_np.asarray(e.hi, dtype=float)).ravel()


def _grid_estimate(cols, name, e):  # a solved value: its discretisation error, no interval
    cols[name] = _np.array([e.value])
    cols[name + "_error"] = _np.array([e.error])


def _diffusivity(r):
    cols = {}
    if r.method != "monte carlo":
        for name in ("diffusivity", "mobility", "stuck_probability", "mean_duration"):
            _grid_estimate(cols, name, getattr(r, name))
        return cols
    for name in ("diffusivity", "mobility", "mean_duration"):
        _estimate(cols, name, getattr(r, name))
    cols["completed"] = _np.array([r.completed], dtype=_np.int64)
    return cols


def _bruteforce(r):
    cols = {}
    _estimate(cols, "diffusivity", r.diffusivity)
    _estimate(cols, "mobility", r.mobility)
    cols["time"] = _np.array([r.time])
    cols["trajectories"] = _np.array([r.trajectories], dtype=_np.int64)
    return cols


def _density(r):
    edges = _np.asarray(r.edges)
    cols = {"v_lo": edges[:-1], "v_hi": edges[1:], "v": _np.asarray(r.centers)}
    if isinstance(r.density, _np.ndarray):  # engine="kolmogorov": the grid's values, no error bars
        cols["density"] = r.density
    else:
        _estimate(cols, "density", r.density)
    return cols


def _series(r):
    """The columns of a result along an axis, as its CSV has them: the axis,
    then each series its class declares (result_fields.hpp), in order."""
    declared = next(d for d in _core._result_fields() if d["python_class"] == type(r).__name__)
    cols = {}
    for f in declared["fields"]:
        name = f["name"].replace(".", "_")
        if f["form"] == "axis":
            cols = {name: _np.asarray(getattr(r, name)), **cols}
        elif f["json"] == "series":
            _estimate(cols, name, getattr(r, name))
    return cols


_correlation = _series
_moments = _series


def _trajectory(r):
    paths = r.paths
    cols = {"path": _np.concatenate([_np.full(len(p), k, dtype=_np.int64) for k, p in enumerate(paths)])
            if paths else _np.zeros(0, dtype=_np.int64)}
    for name in ("t", "x", "mode", "v", "u"):
        cols[name] = (_np.concatenate([getattr(p, name) for p in paths]) if paths
                      else _np.zeros(0, dtype=_np.int64 if name == "mode" else float))
    return cols


def _sweep(r):
    cols = {"tau": _np.asarray(r.tau).ravel(), "noise": _np.asarray(r.noise).ravel()}
    if r.method != "monte carlo":  # engine="kolmogorov": values and discretisation errors
        for name in ("diffusivity", "mobility", "stuck_probability", "mean_duration", "slope", "white_ratio"):
            e = getattr(r, name)
            cols[name] = _np.asarray(e.value, dtype=float).ravel()
            cols[name + "_error"] = _np.asarray(e.error, dtype=float).ravel()
        return cols
    for name in ("diffusivity", "mobility", "mean_duration", "slope", "white_ratio"):
        _estimate(cols, name, getattr(r, name))
    return cols


def _white_noise(r):
    # One row per (time, velocity) pair, time-major (the stationary values on
    # every row): the times alone (the CLI's CSV rows) without velocities, the
    # velocities alone without times, one row with neither.
    times, vs = _np.asarray(r.times), _np.asarray(r.velocities)
    n, m = max(len(times), 1), max(len(vs), 1)
    cols = {name: _np.full(n * m, getattr(r, name)) for name in ("mobility", "diffusivity", "variance")}
    if len(times):
        cols["time"] = _np.repeat(times, m)
        for name in ("first_moment", "autocorrelation"):  # the CSV's value and error (exact or solved)
            cols[name] = _np.repeat(getattr(r, name).value, m)
            cols[name + "_error"] = _np.repeat(getattr(r, name).error, m)
    if len(vs):
        cols["v"] = _np.tile(vs, n)
        cols["stationary_density"] = _np.tile(r.stationary_density, n)
        if len(times):
            cols["transient_density"] = _np.asarray(r.transient_density).ravel()  # NaN at t = 0
    return cols


COLUMNS = {
    "DiffusivityResult": _diffusivity,
    "BruteForceResult": _bruteforce,
    "DensityResult": _density,
    "CorrelationResult": _correlation,
    "MomentsResult": _moments,
    "TrajectoryResult": _trajectory,
    "SweepResult": _sweep,
    "WhiteNoiseResult": _white_noise,
}


def to_columns(self):
    """The result as a table: a dict of equally long 1-D NumPy arrays, one row
    per point (bin, lag, time, recorded point, sweep point, (time, velocity)
    pair of WhiteNoiseResult; one row for a single estimate), an estimate NAME as the columns NAME, NAME_error,
    NAME_lo and NAME_hi (a solved value: NAME and NAME_error)."""
    return COLUMNS[type(self).__name__](self)


def to_dataframe(self):
    """The result as a tidy pandas DataFrame: to_columns(), one row per point
    or bin, with the error and interval columns; df.attrs["meta"] is the
    result's provenance (meta). Needs pandas."""
    try:
        import pandas
    except ImportError as e:
        raise ImportError("to_dataframe() needs pandas (pip install pandas, or apt install python3-pandas); "
                          "to_columns() gives the same table as NumPy arrays") from e
    frame = pandas.DataFrame(to_columns(self))
    frame.attrs["meta"] = self.meta
    return frame


def to_npz(self, path):
    """Write to_columns() as the arrays of a NumPy .npz file at `path` (the
    name as given: no suffix added), with the provenance as the JSON text
    array "meta" (json.loads(str(np.load(path)["meta"])) reads it back), as
    the CLI writes --output: a regular file atomically, nothing left behind
    on failure."""
    buf = _io.BytesIO()
    _np.savez(buf, **to_columns(self), meta=_np.array(_json.dumps(self.meta)))
    _core.write_output_file(_os.fspath(path), buf.getvalue())


_FORMATS = {".json": "to_json", ".csv": "to_csv", ".txt": "to_table"}


def save(self, path):
    """Write the result to `path` in the form its suffix names: .npz
    (to_npz: arrays and meta), .json (to_json), .csv (to_csv, with its
    comment lines of provenance) or .txt (to_table); atomically, as the CLI
    writes --output. Every form says what produced it."""
    path = _os.fspath(path)
    suffix = _os.path.splitext(path)[1].lower()
    if suffix == ".npz":
        return to_npz(self, path)
    if suffix not in _FORMATS:
        raise ValueError(f"save(): cannot tell the format of {path!r}: name it .npz, .json, .csv or .txt")
    _core.write_output_file(path, getattr(self, _FORMATS[suffix])().encode("utf-8"))


def install():
    """Adds the methods to every result class."""
    for name in COLUMNS:
        cls = getattr(_core, name)
        cls.to_columns = to_columns
        cls.to_dataframe = to_dataframe
        cls.to_npz = to_npz
        cls.save = save
