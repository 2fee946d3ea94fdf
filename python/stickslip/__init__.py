# SPDX-License-Identifier: BSD-3-Clause
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
the `stickslip` command's: both come from the library's request structures,
so the same arguments give the same numbers: ``result.to_dict()`` is exactly
the object ``stickslip <command> --format json`` prints (only its "work" part,
the timing, differs between runs). Each keyword is the command's flag with
'-' written '_' (``max_steps`` is ``--max-steps``).

Simulations (the GIL is released while they run; progress=True prints a
progress line on stderr; Ctrl-C lets the blocks in flight finish and raises
KeyboardInterrupt whose ``result`` attribute is the result so far;
checkpoint="run.ckpt" saves a run's state, resume="run.ckpt" continues it
with a result identical to an uninterrupted run's):

    diffusivity(params, ...)   D, mobility M0, mean excursion duration E[t1]
    bruteforce(params, ...)    D_t = var U(t)/t from trajectories on [0, t]
    density(params, ...)       stationary velocity histogram and P(V = 0)
    correlation(params, ...)   <V(0)V(r)>, h(r), h(r)/h(0)
    moments(params, ...)       E[V(t)|v0], E[V(t)^2|v0], P(V(t) = 0), densities
    trajectory(params, ...)    sample paths t, X, mode, V, U
    sweep(params, ...)         D over a grid of noise and tau, slopes, exponents

Each function builds a request (``DiffusivityRequest`` ...) from its
defaults, sets the keywords given and runs it with ``stickslip.run``; the
requests can be used directly too (``r = stickslip.DiffusivityRequest();
r.set("excursions", 2000); stickslip.run(r)``).

Exact white-noise references (no simulation), vectorised over NumPy arrays:
the submodule ``stickslip.analytic``.

Every result says what produced it: ``result.meta`` is {"command": the call,
"settings": every setting as ``--print-config`` writes them, "version",
"revision"}, also in its JSON, its CSV's '#' comment lines and the .npz files
of ``result.save("run.npz")`` (or .json, .csv, .txt; written atomically).
``result.to_dataframe()`` (with pandas) and ``result.to_columns()`` give it as
a table, one row per point or bin, NAME_error, NAME_lo and NAME_hi beside
each estimate NAME. Its notes (``result.warnings``) are raised as
``StickslipWarning``, naming the keywords rather than the CLI's flags.
Results (and Params, the requests) pickle, bit for bit, for
``multiprocessing``, ``joblib`` and caches; a pickle is read only by the
version that wrote it.

Results are objects with NumPy-array attributes; estimates are ``Estimate``
or, along an axis, ``EstimateSeries`` (arrays ``.value``, ``.stderr``,
``.lo``, ``.hi``, ``.ci`` of shape (n, 2)). Every estimate and series, from
every method, has ``.value``, ``.error`` and ``.kind``: ``'sampled'``
(``.error`` the standard error, also ``.stderr``, with ``.ci`` at ``.level``),
``'solved'`` (the estimated discretisation error, no interval) or ``'exact'``
(0), as in the CLI's JSON. ``GridEstimate`` and ``GridEstimateSeries`` are
other names of ``Estimate`` and ``EstimateSeries``.
Invalid input raises ``InvalidParameterError`` (a ValueError) whose text is
the CLI's: ``--<parameter>: <message>``. Runs whose excursions hit the runaway
guard raise ``CappedExcursionsError`` unless ``allow_capped=True``; it is an
``UntrustworthyResultError`` (a RuntimeError), raised also when every
excursion ended within its first step or an estimate is not finite.

Example::

    import stickslip
    p = stickslip.Params()                       # Fig. 2 case
    r = stickslip.diffusivity(p, excursions=2000)
    r.diffusivity.value, r.diffusivity.ci        # m^2/s
    stickslip.analytic.white_noise_reference(p.replace(tau=0))["diffusivity"]
"""

from . import _core  # noqa: F401
from ._core import (  # noqa: F401  (re-exported)
    BruteForceRequest,
    BruteForceResult,
    CappedExcursionsError,
    UntrustworthyResultError,
    CorrelationRequest,
    CorrelationResult,
    DensityRequest,
    DensityResult,
    DiffusivityRequest,
    DiffusivityResult,
    Estimate,
    EstimateSeries,
    GridEstimate,
    GridEstimateSeries,
    Histogram,
    InvalidParameterError,
    MomentsRequest,
    MomentsResult,
    Params,
    Path,
    Scales,
    SpectrumRequest,
    SpectrumResult,
    SweepExponent,
    SweepRequest,
    SweepResult,
    SweepWhiteLimit,
    TrajectoryRequest,
    TrajectoryResult,
    __version__,
    keyword_of_flag,
)
from . import analytic  # noqa: E402,F401
from ._commands import StickslipWarning, run  # noqa: E402,F401
from . import _tables  # noqa: E402

_tables.install()  # to_columns, to_dataframe, to_npz, save on every result class

_REQUESTS = (BruteForceRequest, CorrelationRequest, DensityRequest, DiffusivityRequest, MomentsRequest,
             SpectrumRequest, SweepRequest, TrajectoryRequest)
# Show (and pickle) the compiled classes under the names users import.
for _cls in (BruteForceResult, CorrelationResult, DensityResult, DiffusivityResult, Estimate, EstimateSeries,
             GridEstimateSeries, Histogram, MomentsResult, Params, Path, Scales, SpectrumResult, SweepExponent,
             SweepResult,
             SweepWhiteLimit, TrajectoryResult,
             InvalidParameterError, UntrustworthyResultError, CappedExcursionsError, StickslipWarning) + _REQUESTS:
    _cls.__module__ = __name__
run.__module__ = __name__
del _cls

__all__ = [
    "Params", "Scales", "Estimate", "EstimateSeries", "GridEstimate", "GridEstimateSeries", "Histogram", "Path",
    "DiffusivityResult", "BruteForceResult", "DensityResult", "CorrelationResult", "MomentsResult",
    "TrajectoryResult", "SweepResult", "SweepExponent", "SweepWhiteLimit", "SpectrumResult",
    "DiffusivityRequest", "BruteForceRequest", "DensityRequest", "CorrelationRequest", "MomentsRequest",
    "TrajectoryRequest", "SweepRequest", "SpectrumRequest", "run",
    "InvalidParameterError", "UntrustworthyResultError", "CappedExcursionsError", "StickslipWarning",
    "keyword_of_flag",
    "diffusivity", "bruteforce", "density", "correlation", "moments", "trajectory", "sweep", "spectrum",
    "logspace", "analytic", "__version__",
]


def logspace(lo, hi, n):
    """n values from lo to hi evenly spaced in log, exactly as the CLI's ``lo:hi:n``
    (endpoints exact), e.g. ``sweep(noise=logspace(1, 10, 5))`` reproduces
    ``stickslip sweep --noise 1:10:5`` bit for bit. Returns a list of floats."""
    r = SweepRequest()
    r.set("noise", f"{float(lo)!r}:{float(hi)!r}:{n}")  # the library's parser: its checks and messages
    return r.get("noise")


from ._commands import command as _command  # noqa: E402

diffusivity = _command("diffusivity", DiffusivityRequest, """\
D, mobility M0 and mean long-excursion duration E[t1] from N long excursions.

    D = sum (U - M0 t)^2 / sum t over i.i.d. long excursions (displacement U [m],
    duration t [s]): the renewal-reward form of lim var U(t)/t, correct for any
    mobility, with delta-method confidence intervals. Same as
    ``stickslip diffusivity``; where the control variate's pilot measures a
    tail of D's influence function so heavy that the interval may cover well
    below its level (``control_variate`` ``influence.flagged``), a warning
    says so (without the pilot: below 5000 excursions). With rel_precision > 0 the run goes
    on in batches until D's interval is that narrow (`.precision` says how it
    ended). With engine="kolmogorov" nothing is sampled: the Kolmogorov
    equations are solved on grids to the relative precision rel_precision of D
    (default 1e-3), for coloured noise of every tau' > 0.""", """\
    DiffusivityResult
        .diffusivity [m^2/s], .mobility [m/s], .mean_duration [s] (Estimate:
        .value, .stderr, .ci), .completed, .capped, .warnings, .params;
        .to_dict() is the CLI's JSON (nondimensional values included). With
        engine="kolmogorov": .diffusivity, .mobility, .stuck_probability and
        .mean_duration are Estimates of kind 'solved' (.value, .error: the
        estimated discretisation error), and .method is "kolmogorov".""", """

    Example
    -------
    >>> r = stickslip.diffusivity(stickslip.Params(), excursions=2000, seed=3)
    >>> r.diffusivity.value, r.diffusivity.ci""")

bruteforce = _command("bruteforce", BruteForceRequest, """\
Brute-force D_t = var U(t)/t (the paper's eq. 13) from N' trajectories on [0, t].

    Biased against D by O(1/t); for comparison with diffusivity(). Same as
    ``stickslip bruteforce``.""", """\
    BruteForceResult
        .diffusivity (D_t, m^2/s) and .mobility (U(t)/t, m/s) as Estimate,
        .time, .trajectories, .x0; .to_dict() is the CLI's JSON.""")

density = _command("density", DensityRequest, """\
Stationary velocity density as a histogram with error bars, and P(V = 0).

    Renewal-reward ratios over long excursions (time spent in each bin during an
    excursion / its duration): exact in the limit of many excursions, no
    burn-in. The atom at V = 0 (the object sticks; positive for coloured noise)
    is reported apart, so sum(density * widths) + stuck_probability + below + above = 1.
    The excursions are diffusivity()'s with the same seed, so D, M0 and E[t1]
    come with it, identical. Same as ``stickslip density``; range is (lo, hi)
    in m/s.""", """\
    DensityResult
        .edges (bins + 1,) [m/s], .centers (bins,), .density (EstimateSeries,
        (bins,), s/m), .stuck_probability, .below, .above (Estimate, probabilities),
        .mean [m/s], .variance [m^2/s^2], .diffusivity, .mobility,
        .mean_duration; .to_dict() is the CLI's JSON.""")

correlation = _command("correlation", CorrelationRequest, """\
Stationary autocorrelation <V(0)V(r)>, covariance h(r) = <V(0)V(r)> - M0^2 and h(r)/h(0).

    Renewal-reward ratios over long excursions, each continued past its end by
    the largest lag (exact: the process regenerates), with delta-method
    intervals (the paper's Figs. 5 and 8). Same as ``stickslip correlation``.""", """\
    CorrelationResult
        .lag (lags + 1,) [s], .autocorrelation, .covariance [m^2/s^2] and
        .normalised_covariance (EstimateSeries, (lags + 1,)), .mean [m/s], .diffusivity,
        .mobility, .mean_duration; .to_dict() is the CLI's JSON.""")

moments = _command("moments", MomentsRequest, """\
Transient statistics from V(0) = v0: E[V(t)|v0], E[V(t)^2|v0], P(V(t) = 0), densities.

    Plain means over independent trajectories from V(0) = v0 with X(0) drawn
    from its stationary law N(0, 1/tau) (the paper's Table I and Fig. 7
    set-up). Same as ``stickslip moments``. times is a sequence of floats (or
    None: Table I's); the inclusion engine rounds them to whole steps
    (result.time has the times used).""", """\
    MomentsResult
        .time (n,) [s], .first_moment [m/s], .second_moment [m^2/s^2], .stuck_probability
        (EstimateSeries, (n,)), .density (list of n Histogram, or []);
        .to_dict() is the CLI's JSON.""")

trajectory = _command("trajectory", TrajectoryRequest, """\
Sample paths: t, X, mode, V, U.

    Excursion mode (paths=0, default): long excursion number `index` of stream
    `seed`, the very excursion diffusivity() runs with that index (the paper's
    Figs. 2 and 3). Path mode (paths=N > 0): N independent paths on [0, time]
    from (x0, v0) (Fig. 6, right). Same as ``stickslip trajectory``.""", """\
    TrajectoryResult
        .paths: list of Path with arrays .t [s], .x [s^-1/2], .mode (-1/0/+1),
        .v [m/s], .u [m]; .path is the first; excursion mode adds
        .displacement [m], .duration [s], .complete. .to_dict() is the CLI's JSON.""")

sweep = _command("sweep", SweepRequest, """\
D, M0 and E[t1] over a grid of noise intensities and correlation times.

    The paper's Figs. 4 and 9: every (tau, noise) point is a diffusivity() run
    with its own random streams (point k uses sample indices from k*2^40), the
    local slope d log D / d log noise (central differences) and, per tau, the
    fitted exponent of D ~ noise^alpha with chi^2/dof. Same as
    ``stickslip sweep``. params gives friction, relaxation and bias (its noise
    and tau are not used); noise and tau are sequences (sorted and
    deduplicated), e.g. noise=logspace(1, 10, 5). With engine="kolmogorov"
    every point is solved without sampling, to the relative precision
    rel_precision of D (default 1e-3; 1e-2 is about 10 times faster).""", """\
    SweepResult
        Every array has shape (len(taus), len(noises)): axis 0 is .taus,
        axis 1 .noises (points an interrupted sweep did not reach are NaN):
        .noise, .tau (each point's), .diffusivity, .mobility,
        .mean_duration, .slope (EstimateSeries); .shape; .exponents (one
        SweepExponent per tau). .to_dict() is the CLI's JSON. With
        engine="kolmogorov" they are solved series (kind 'solved', .error
        the estimated discretisation errors), .stuck_probability too, and
        .method is "kolmogorov".""")

spectrum = _command("spectrum", SpectrumRequest, """\
Two-sided velocity power spectrum S(w) = int C(t) exp(-i w t) dt over all t, S(0) = D.

    C is the stationary autocovariance of V and w the angular frequency
    [rad/s]; a one-sided spectrum in Hz is 2 S(2 pi f). By default nothing
    is sampled: the Kolmogorov engine solves (i w - L) phi = V - M0 on its
    grids, one complex sparse LU per frequency and grid, and extrapolates
    like D; with white noise (tau=0) the closed form without drag
    (relaxation=inf), the velocity's Fokker-Planck chain with drag. engine="inclusion" or "pdmp" samples long excursions instead (the
    regenerative estimator: each cycle's transform and the geometric sum of
    the cross-cycle terms; excursions=, seed=, sample_dt= apply, and white
    noise with drag or any law is allowed). Same as ``stickslip spectrum``;
    frequencies is a sequence of floats >= 0 (None: 0 and 0.01 to 100 over
    the time unit, one per decade).""", """\
    SpectrumResult
        .frequency (n,) [rad/s], .spectrum (EstimateSeries of kind 'solved',
        'exact' or 'sampled', (n,), m^2/s), .diffusivity, .mobility
        (Estimate), .excursions, .method; .to_dict() is the CLI's JSON.""", """

    Example
    -------
    >>> r = stickslip.spectrum(stickslip.Params(), frequencies=[0, 1, 10])
    >>> r.spectrum.value, r.spectrum.error""")

