"""stickslip: diffusivity and velocity statistics of an object with dry friction
under white or coloured (Ornstein-Uhlenbeck) noise.

Model, SI units (m, s)::

    dV/dt + friction*sgn(V) = -V/relaxation + bias + sqrt(noise/2)*X(t)
    tau dX = -X dt + sqrt(2) dW,      E[X(0)X(t)] = exp(-|t|/tau)/tau

The object sticks (V = 0) while |bias + force| <= friction. Noise convention:
as tau -> 0 the random force sqrt(noise/2)*X tends to a white noise of
intensity Gamma = noise (<f(t)f(s)> = noise*delta(t-s)); tau = 0 is that white
noise. The nondimensional system takes friction = noise = 1 (time unit
noise/friction^2, velocity unit noise/friction, length unit noise^2/friction^3,
diffusivity unit noise^3/friction^4): see Params.nondimensional() and
Params.scales().

Every default is the paper's Fig. 2 case (friction 3.84 m/s^2, noise 5 m^2/s^3,
tau 0.5 s, relaxation 0.067 s, bias 0.342 m/s^2) and every other default is
the `stickslip` command's, so the same arguments give the same numbers:
``result.to_dict()`` is exactly the object ``stickslip <command> --format
json`` prints (only its "work" part, the timing, differs between runs).

Simulations (the GIL is released while they run; Ctrl-C stops them and raises
KeyboardInterrupt; progress=True prints a progress line on stderr):

    diffusivity(params, ...)   D, mobility M0, mean excursion duration E[t1]
    bruteforce(params, ...)    D_t = var U(t)/t from trajectories on [0, t]
    density(params, ...)       stationary velocity histogram and P(V = 0)
    correlation(params, ...)   <V(0)V(r)>, h(r), h(r)/h(0)
    moments(params, ...)       E[V(t)|v0], E[V(t)^2|v0], P(V(t) = 0), densities
    trajectory(params, ...)    sample paths t, X, mode, V, U
    sweep(params, ...)         D over a grid of noise and tau, slopes, exponents

Exact white-noise references (no simulation), vectorised over NumPy arrays:
the submodule ``stickslip.analytic``.

Results are objects with NumPy-array attributes; estimates are ``Estimate``
(``.value``, ``.stderr``, ``.ci``) or, along an axis, ``EstimateSeries``
(arrays ``.value``, ``.stderr``, ``.lo``, ``.hi``, ``.ci`` of shape (n, 2)).
Invalid input raises ``InvalidParameterError`` (a ValueError) whose text is
the CLI's: ``--<parameter>: <message>``. Runs whose excursions hit the runaway
guard raise ``CappedExcursionsError`` (a RuntimeError) unless
``allow_capped=True``.

Example::

    import stickslip
    p = stickslip.Params()                       # Fig. 2 case
    r = stickslip.diffusivity(p, excursions=2000)
    r.diffusivity.value, r.diffusivity.ci        # m^2/s
    stickslip.analytic.white_noise_reference(p.replace(tau=0))["diffusivity"]
"""

import math as _math
import numbers as _numbers

from . import _core
from ._core import (  # noqa: F401  (re-exported)
    BruteForceResult,
    CappedExcursionsError,
    CorrelationResult,
    DensityResult,
    DiffusivityResult,
    Estimate,
    EstimateSeries,
    Histogram,
    InvalidParameterError,
    MomentsResult,
    Params,
    Path,
    Scales,
    SweepExponent,
    SweepResult,
    TrajectoryResult,
    __version__,
)
from . import analytic  # noqa: E402,F401

# Show (and pickle) the compiled classes under the names users import.
for _cls in (BruteForceResult, CorrelationResult, DensityResult, DiffusivityResult, Estimate, EstimateSeries,
             Histogram, MomentsResult, Params, Path, Scales, SweepExponent, SweepResult, TrajectoryResult):
    _cls.__module__ = __name__
for _cls in (InvalidParameterError, CappedExcursionsError):
    _cls.__module__ = __name__
del _cls

__all__ = [
    "Params", "Scales", "Estimate", "EstimateSeries", "Histogram", "Path",
    "DiffusivityResult", "BruteForceResult", "DensityResult", "CorrelationResult", "MomentsResult",
    "TrajectoryResult", "SweepResult", "SweepExponent",
    "InvalidParameterError", "CappedExcursionsError",
    "diffusivity", "bruteforce", "density", "correlation", "moments", "trajectory", "sweep",
    "logspace", "analytic", "__version__",
]

# ---- argument checks: the CLI's messages, so errors read the same everywhere ----------


def _invalid(name, message):
    e = InvalidParameterError(f"--{name}: {message}")
    e.parameter = name
    e.message = message
    return e


def _number(name, x):
    """A float; NaN and non-numbers are rejected with the CLI's message."""
    if isinstance(x, str):
        try:
            v = float(x)
        except ValueError:
            raise _invalid(name, f"{name} must be a number, got '{x}'") from None
    else:
        try:
            v = float(x)
        except (TypeError, ValueError):
            raise _invalid(name, f"{name} must be a number, got '{x}'") from None
    if _math.isnan(v):
        raise _invalid(name, f"{name} must be a number, got NaN")
    return v


def _optional_number(name, x):
    return None if x is None else _number(name, x)


def _count(name, x):
    """A non-negative integer (1e4 is accepted, as by the CLI)."""
    if isinstance(x, bool):
        raise _invalid(name, f"{name} must be a non-negative integer, got '{x}'")
    if isinstance(x, _numbers.Integral):
        v = int(x)
        if v < 0 or v >= 2**64:
            raise _invalid(name, f"{name} must be a non-negative integer, got '{x}'")
        return v
    v = _number(name, x)
    if not (v >= 0) or v != _math.floor(v) or v > 1.8e19:
        raise _invalid(name, f"{name} must be a non-negative integer, got '{x}'")
    return int(v)


def _int_at_most(name, x, most):
    v = _count(name, x)
    if v > most:
        raise _invalid(name, f"{name} must be at most {most}, got '{x}'")
    return v


def _seed(x):
    if isinstance(x, bool) or not isinstance(x, _numbers.Integral) or not 0 <= int(x) < 2**64:
        raise _invalid("seed", f"seed must be an integer in [0, 2^64), got '{x}'")
    return int(x)


def _threads(x):
    v = _count("threads", x)
    if v > 4096:
        raise _invalid("threads", "threads must be between 0 and 4096")
    return v


def _numbers_list(name, xs):
    if isinstance(xs, (str, bytes)):
        raise TypeError(f"{name}: expected a sequence of numbers, got a string")
    try:
        items = list(xs.ravel()) if hasattr(xs, "ravel") else list(xs)
    except TypeError:
        items = [xs]  # a single number
    return [_number(name, x) for x in items]


def _range(x):
    if x is None:
        return 0.0, 0.0
    try:
        lo, hi = x
    except (TypeError, ValueError):
        raise _invalid("range", f"range must be 'lo,hi' in m/s, got '{x}'") from None
    lo, hi = _number("range", lo), _number("range", hi)
    if not lo < hi:
        raise _invalid("range", f"range needs lo < hi, got '{lo!r},{hi!r}'")
    return lo, hi


def _params(params):
    if params is None:
        return Params()
    if isinstance(params, Params):
        return params
    if isinstance(params, dict):
        return Params(**params)
    raise TypeError(f"params must be a stickslip.Params (or a dict of its fields), got {type(params).__name__}")


def _engine(engine, dt, grid, lattice_bound, stop_rule, white_level, max_steps):
    return _core._EngineSettings(
        engine=str(engine),
        dt=_number("dt", dt),
        grid=_number("grid", grid),
        lattice_bound=_number("lattice-bound", lattice_bound),
        stop_rule=str(stop_rule),
        white_level=_number("white-level", white_level),
        max_steps=_count("max-steps", max_steps),
    )


def _run(seed, threads, level, progress):
    return _core._RunArgs(seed=_seed(seed), threads=_threads(threads), level=_number("level", level),
                          progress=bool(progress))


def logspace(lo, hi, n):
    """n values from lo to hi evenly spaced in log, exactly as the CLI's ``lo:hi:n``
    (endpoints exact), e.g. ``sweep(noise=logspace(1, 10, 5))`` reproduces
    ``stickslip sweep --noise 1:10:5`` bit for bit. Returns a list of floats."""
    lo, hi, n = _number("lo", lo), _number("hi", hi), _count("n", n)
    if not (_math.isfinite(lo) and _math.isfinite(hi) and lo > 0 and hi > 0 and 1 <= n <= 1000000):
        raise ValueError("logspace needs finite lo, hi > 0 and 1 <= n <= 1000000")
    out = [_math.exp(_math.log(lo) + (_math.log(hi) - _math.log(lo)) * (0.0 if n == 1 else k / (n - 1)))
           for k in range(n)]
    out[0] = lo
    if n > 1:
        out[-1] = hi
    return out


# ---- shared documentation -------------------------------------------------------------

_PARAMS_DOC = """\
    params : Params, optional
        Physical parameters, SI units (default Params(): the paper's Fig. 2 case,
        friction 3.84 m/s^2, noise 5 m^2/s^3, tau 0.5 s, relaxation 0.067 s,
        bias 0.342 m/s^2). A dict of Params fields is accepted too."""

_ENGINE_DOC = """\
    engine : {"inclusion", "pdmp"}
        "inclusion" (default): time stepping of the differential inclusion with
        the exact OU step law, step `dt`. "pdmp": exact event-driven simulation
        with lattice jump noise of step `grid` (needs tau > 0).
    dt : float
        Inclusion time step [s] (default 1e-4).
    grid : float
        PDMP lattice step delta of the noise [s^-1/2] (default 0.125).
    stop_rule : {"auto", "bridge", "stuck"}
        Inclusion end-of-excursion test: "auto" (bridge when dt <= tau/10, else
        stuck), "bridge" (rule Q, flat in dt), "stuck" (rule P).
    lattice_bound : float
        PDMP lattice half-width L [s^-1/2]; 0 (default) chooses it.
    white_level : float
        White noise only: regeneration velocity levels +-c [m/s]; 0 chooses c.
    max_steps : int
        Runaway guard: most steps (inclusion) or events (pdmp) per long
        excursion or trajectory (default 200_000_000)."""

_RUN_DOC = """\
    seed : int
        Random seed in [0, 2^64) (default 1). Sample k uses only the Philox
        stream (seed, k): results are bitwise identical for any `threads`.
    threads : int
        Worker threads; 0 (default) = all cores.
    level : float
        Confidence level of the intervals, in (0, 1) (default 0.95).
    progress : bool
        Print a progress line on sys.stderr (default False)."""

_RAISES_DOC = """\
    Raises
    ------
    InvalidParameterError (ValueError)
        Invalid input; str(e) is the CLI's "--<parameter>: <message>".
    CappedExcursionsError (RuntimeError)
        Some excursions hit `max_steps` (unless allow_capped=True).
    KeyboardInterrupt
        Ctrl-C (or any exception raised by a signal handler) while it runs: the
        run stops within one block of 64 samples per thread."""


def _doc(text):
    def put(f):
        f.__doc__ = text.format(params=_PARAMS_DOC, engine=_ENGINE_DOC, run=_RUN_DOC, raises=_RAISES_DOC)
        return f
    return put


# ---- simulations ------------------------------------------------------------------------


@_doc("""D, mobility M0 and mean long-excursion duration E[t1] from N long excursions.

    D = sum (U - M0 t)^2 / sum t over i.i.d. long excursions (displacement U [m],
    duration t [s]): the renewal-reward form of lim var U(t)/t, correct for any
    mobility, with delta-method confidence intervals. Same as
    ``stickslip diffusivity``.

    Parameters
    ----------
{params}
    excursions : int
        Number N of long excursions, >= 2 (default 10000; below 5000 the
        standard errors are themselves noisy and a warning says so).
    estimator : {{"renewal", "paper"}}
        "renewal" (default, correct) or "paper" (eq. 12, Var U / E t: biased
        when M0 != 0; for reproducing the paper's numbers only).
    allow_capped : bool
        Return a (biased) result even if some excursions hit `max_steps`.
    rel_precision : float
        Precision on demand: when > 0 (e.g. 0.01), run in batches (the first
        of `excursions`) until the interval half-width of D is at most this
        fraction of D, or `max_excursions` have run; `.precision` then says
        how it ended. The stopping time depends on the data, so the coverage
        is slightly below `level`. 0 (default): exactly `excursions`.
    max_excursions : int
        Cap of `rel_precision` (default 100_000_000).
{engine}
{run}

    Returns
    -------
    DiffusivityResult
        .diffusivity [m^2/s], .mobility [m/s], .mean_duration [s] (Estimate:
        .value, .stderr, .ci), .completed, .capped, .warnings, .params;
        .to_dict() is the CLI's JSON (nondimensional values included).

{raises}

    Example
    -------
    >>> r = stickslip.diffusivity(stickslip.Params(), excursions=2000, seed=3)
    >>> r.diffusivity.value, r.diffusivity.ci
""")
def diffusivity(params=None, *, excursions=10000, engine="inclusion", dt=1e-4, grid=0.125, stop_rule="auto",
                estimator="renewal", allow_capped=False, seed=1, threads=0, level=0.95, progress=False,
                lattice_bound=0.0, white_level=0.0, max_steps=200_000_000, rel_precision=0.0,
                max_excursions=100_000_000):
    return _core._diffusivity(
        _params(params), _engine(engine, dt, grid, lattice_bound, stop_rule, white_level, max_steps),
        _count("excursions", excursions), str(estimator), bool(allow_capped), float(rel_precision),
        _count("max-excursions", max_excursions), _run(seed, threads, level, progress))


@_doc("""Brute-force D_t = var U(t)/t (the paper's eq. 13) from N' trajectories on [0, t].

    Biased against D by O(1/t); for comparison with diffusivity(). Same as
    ``stickslip bruteforce``.

    Parameters
    ----------
{params}
    time : float
        Horizon t [s] (default 10).
    trajectories : int
        Number N' of independent trajectories, >= 2 (default 1000).
    x0 : float or None
        Initial noise X(0) [s^-1/2]; None (default): the upper threshold x*
        (pdmp: the first lattice point above it), where the object starts moving.
    v0 : float
        Initial velocity [m/s] (default 0).
{engine}
{run}

    Returns
    -------
    BruteForceResult
        .diffusivity (D_t, m^2/s) and .mobility (U(t)/t, m/s) as Estimate,
        .time, .trajectories, .x0; .to_dict() is the CLI's JSON.

{raises}
""")
def bruteforce(params=None, *, time=10.0, trajectories=1000, x0=None, v0=0.0, engine="inclusion", dt=1e-4,
               grid=0.125, stop_rule="auto", seed=1, threads=0, level=0.95, progress=False, lattice_bound=0.0,
               white_level=0.0, max_steps=200_000_000):
    return _core._bruteforce(
        _params(params), _engine(engine, dt, grid, lattice_bound, stop_rule, white_level, max_steps),
        _number("time", time), _count("trajectories", trajectories), _optional_number("x0", x0),
        _number("v0", v0), _run(seed, threads, level, progress))


@_doc("""Stationary velocity density as a histogram with error bars, and P(V = 0).

    Renewal-reward ratios over long excursions (time spent in each bin during an
    excursion / its duration): exact in the limit of many excursions, no
    burn-in. The atom at V = 0 (the object sticks; positive for coloured noise)
    is reported apart, so sum(density * widths) + stuck + below + above = 1.
    The excursions are diffusivity()'s with the same seed, so D, M0 and E[t1]
    come with it, identical. Same as ``stickslip density``.

    Parameters
    ----------
{params}
    excursions : int
        Number of long excursions, >= 2 (default 10000).
    bins : int
        Number of equal velocity bins (default 80).
    range : (float, float) or None
        Velocity range (lo, hi) [m/s]; None (default): the velocities seen by
        the first 256 excursions, padded by 10%.
    sample_dt : float
        PDMP only: sampling interval of the path [s]; 0 (default) = dt.
    allow_capped : bool
        Return a (biased) result even if some excursions hit `max_steps`.
{engine}
{run}

    Returns
    -------
    DensityResult
        .edges (bins + 1,) [m/s], .centers (bins,), .density (EstimateSeries,
        (bins,), s/m), .stuck, .below, .above (Estimate, probabilities),
        .mean [m/s], .variance [m^2/s^2], .diffusivity, .mobility,
        .mean_duration; .to_dict() is the CLI's JSON.

{raises}
""")
def density(params=None, *, excursions=10000, bins=80, range=None, sample_dt=0.0, engine="inclusion", dt=1e-4,
            grid=0.125, stop_rule="auto", allow_capped=False, seed=1, threads=0, level=0.95, progress=False,
            lattice_bound=0.0, white_level=0.0, max_steps=200_000_000):
    lo, hi = _range(range)
    return _core._density(
        _params(params), _engine(engine, dt, grid, lattice_bound, stop_rule, white_level, max_steps),
        _count("excursions", excursions), _int_at_most("bins", bins, 100000), lo, hi,
        _number("sample-dt", sample_dt), bool(allow_capped), _run(seed, threads, level, progress))


@_doc("""Stationary autocorrelation <V(0)V(r)>, covariance h(r) = <V(0)V(r)> - M0^2 and h(r)/h(0).

    Renewal-reward ratios over long excursions, each continued past its end by
    the largest lag (exact: the process regenerates), with delta-method
    intervals (the paper's Figs. 5 and 8). Same as ``stickslip correlation``.

    Parameters
    ----------
{params}
    excursions : int
        Number of long excursions, >= 2 (default 10000).
    max_lag : float
        Largest lag r [s]; 0 (default) = 5 time units (5 noise/friction^2).
    lags : int
        Number of lag intervals: lags 0, max_lag/lags, ..., max_lag (rounded to
        the sampling grid) (default 50).
    sample_dt : float
        PDMP only: sampling interval of the path [s]; 0 (default) = dt.
    allow_capped : bool
        Return a (biased) result even if some excursions hit `max_steps`.
{engine}
{run}

    Returns
    -------
    CorrelationResult
        .lag (lags + 1,) [s], .autocorrelation, .covariance [m^2/s^2] and
        .normalised (EstimateSeries, (lags + 1,)), .mean [m/s], .diffusivity,
        .mobility, .mean_duration; .to_dict() is the CLI's JSON.

{raises}
""")
def correlation(params=None, *, excursions=10000, max_lag=0.0, lags=50, sample_dt=0.0, engine="inclusion", dt=1e-4,
                grid=0.125, stop_rule="auto", allow_capped=False, seed=1, threads=0, level=0.95, progress=False,
                lattice_bound=0.0, white_level=0.0, max_steps=200_000_000):
    return _core._correlation(
        _params(params), _engine(engine, dt, grid, lattice_bound, stop_rule, white_level, max_steps),
        _count("excursions", excursions), _number("max-lag", max_lag), _int_at_most("lags", lags, 100000),
        _number("sample-dt", sample_dt), bool(allow_capped), _run(seed, threads, level, progress))


_TABLE_I_TIMES = (0.05, 0.125, 0.25, 0.5, 1.0, 2.5)


@_doc("""Transient statistics from V(0) = v0: E[V(t)|v0], E[V(t)^2|v0], P(V(t) = 0), densities.

    Plain means over independent trajectories from V(0) = v0 with X(0) drawn
    from its stationary law N(0, 1/tau) (the paper's Table I and Fig. 7
    set-up). Same as ``stickslip moments``.

    Parameters
    ----------
{params}
    times : sequence of float or None
        Times t >= 0 [s], any order; None (default): Table I's t' = 0.05,
        0.125, 0.25, 0.5, 1, 2.5 time units (noise/friction^2). The inclusion
        engine rounds them to whole steps (result.time has the times used).
    v0 : float or None
        Initial velocity [m/s]; None (default): 1 velocity unit, noise/friction.
    x0 : float or None
        Initial noise X(0) [s^-1/2]; None (default): drawn from N(0, 1/tau) for
        each trajectory. Ignored for white noise.
    trajectories : int
        Number of independent trajectories, >= 2 (default 10000).
    density : bool
        Also histogram V(t) at every time (default False).
    bins : int
        Number of velocity bins of the densities (default 60).
    range : (float, float) or None
        Velocity range (lo, hi) [m/s] of the densities; None: automatic.
{engine}
{run}

    Returns
    -------
    MomentsResult
        .time (n,) [s], .first_moment [m/s], .second_moment [m^2/s^2], .stuck
        (EstimateSeries, (n,)), .density (list of n Histogram, or []);
        .to_dict() is the CLI's JSON.

{raises}
""")
def moments(params=None, *, times=None, v0=None, x0=None, trajectories=10000, density=False, bins=60, range=None,
            engine="inclusion", dt=1e-4, grid=0.125, stop_rule="auto", seed=1, threads=0, level=0.95, progress=False,
            lattice_bound=0.0, white_level=0.0, max_steps=200_000_000):
    p = _params(params)
    sc = p.scales()
    times = [t * sc.time for t in _TABLE_I_TIMES] if times is None else _numbers_list("times", times)
    v0 = sc.velocity if v0 is None else _number("v0", v0)
    lo, hi = _range(range)
    return _core._moments(
        p, _engine(engine, dt, grid, lattice_bound, stop_rule, white_level, max_steps), v0,
        _optional_number("x0", x0), times, _count("trajectories", trajectories), bool(density),
        _int_at_most("bins", bins, 100000), lo, hi, _run(seed, threads, level, progress))


@_doc("""Sample paths: t, X, mode, V, U.

    Excursion mode (paths=0, default): long excursion number `index` of stream
    `seed`, the very excursion diffusivity() runs with that index (the paper's
    Figs. 2 and 3). Path mode (paths=N > 0): N independent paths on [0, time]
    from (x0, v0) (Fig. 6, right). Same as ``stickslip trajectory``.

    Parameters
    ----------
{params}
    index : int
        Excursion number (excursion mode) (default 0).
    paths : int
        Number of independent paths, at most 1000; 0 (default): one long
        excursion instead.
    time : float
        Path length [s] (path mode) (default 2).
    x0 : float or None
        Initial noise X(0) [s^-1/2] (path mode); None: the upper threshold x*.
    v0 : float
        Initial velocity [m/s] (path mode) (default 0).
    every : float
        Recording interval [s]; 0 (default) = every step (inclusion) or event
        (pdmp) of an excursion, time/1000 for paths.
    max_points : int
        Refuse to record more points than this per path (default 5_000_000).
{engine}
    seed : int
        Random seed in [0, 2^64) (default 1).
    threads : int
        Worker threads (path mode); 0 (default) = all cores.
    progress : bool
        Accepted for symmetry; trajectories report no progress.

    Returns
    -------
    TrajectoryResult
        .paths: list of Path with arrays .t [s], .x [s^-1/2], .mode (-1/0/+1),
        .v [m/s], .u [m]; .path is the first; excursion mode adds
        .displacement [m], .duration [s], .complete. .to_dict() is the CLI's JSON.

{raises}
""")
def trajectory(params=None, *, index=0, paths=0, time=2.0, x0=None, v0=0.0, every=0.0, max_points=5_000_000,
               engine="inclusion", dt=1e-4, grid=0.125, stop_rule="auto", seed=1, threads=0, progress=False,
               lattice_bound=0.0, white_level=0.0, max_steps=200_000_000):
    return _core._trajectory(
        _params(params), _engine(engine, dt, grid, lattice_bound, stop_rule, white_level, max_steps),
        _count("index", index), _count("paths", paths), _number("time", time), _optional_number("x0", x0),
        _number("v0", v0), _number("every", every), _count("max-points", max_points),
        _run(seed, threads, 0.95, progress))


@_doc("""D, M0 and E[t1] over a grid of noise intensities and correlation times.

    The paper's Figs. 4 and 9: every (tau, noise) point is a diffusivity() run
    with its own random streams (point k uses sample indices from k*2^40), the
    local slope d log D / d log noise (central differences) and, per tau, the
    fitted exponent of D ~ noise^alpha with chi^2/dof. Same as
    ``stickslip sweep``.

    Parameters
    ----------
    params : Params, optional
        friction, relaxation and bias (its noise and tau are not used);
        default Params().
    noise : sequence of float
        Noise intensities Gamma [m^2 s^-3], > 0 (default logspace(1, 10, 5),
        the CLI's 1:10:5). Sorted and deduplicated.
    tau : sequence of float
        Correlation times [s], >= 0 (default [0.125, 0.25, 0.5, 1]). Sorted and
        deduplicated.
    excursions : int
        Long excursions per point, >= 2 (default 10000).
    estimator : {{"renewal", "paper"}}
        As in diffusivity().
    allow_capped : bool
        Return (biased) results even if some excursions hit `max_steps`.
{engine}
{run}

    Returns
    -------
    SweepResult
        Points tau-major (for each tau, the noises increasing): .noise, .tau
        (points,), .diffusivity, .mobility, .mean_duration, .slope
        (EstimateSeries, (points,)); .shape = (len(taus), len(noises)) for
        reshaping; .exponents (one SweepExponent per tau). .to_dict() is the
        CLI's JSON.

{raises}
""")
def sweep(params=None, *, noise=None, tau=None, excursions=10000, engine="inclusion", dt=1e-4, grid=0.125,
          stop_rule="auto", estimator="renewal", allow_capped=False, seed=1, threads=0, level=0.95, progress=False,
          lattice_bound=0.0, white_level=0.0, max_steps=200_000_000):
    noises = logspace(1, 10, 5) if noise is None else _numbers_list("noise", noise)
    taus = [0.125, 0.25, 0.5, 1.0] if tau is None else _numbers_list("tau", tau)
    return _core._sweep(
        _params(params), _engine(engine, dt, grid, lattice_bound, stop_rule, white_level, max_steps), noises, taus,
        _count("excursions", excursions), str(estimator), bool(allow_capped), _run(seed, threads, level, progress))
