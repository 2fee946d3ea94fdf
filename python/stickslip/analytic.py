# SPDX-License-Identifier: BSD-3-Clause
"""Exact white-noise references (no simulation), vectorised over NumPy arrays.

For white noise (tau = 0) the velocity is the diffusion

    dV = (b(V) - friction*sgn(V)) dt + sqrt(noise) dW,    b(v) = -v/relaxation + bias,

(noise convention: intensity Gamma = noise, Fokker-Planck diffusion coefficient
noise/2). These functions give its exact stationary law and, for pure dry
friction (relaxation = inf, bias = 0), the closed forms of Touchette, Van der
Straeten and Just (2010) restated in the project's variables (docs/theory.md, section 8); with drag or a bias
the transient quantities come from the Fokker-Planck solver (FokkerPlanck).
``params.tau`` is ignored throughout: these are the references of the
white-noise limit of any tau. SI units everywhere.

Array arguments broadcast against each other (NumPy rules); the result has the
broadcast shape, or is a float when every argument is a scalar.

    hayakawa_density(params, v)          stationary density p(v) [s/m]
    hayakawa_probability(params, a, b)   P(a <= V <= b)
    hayakawa_potential(params, v)        -log(p(v)/p(mode))
    hayakawa_moments(params)             {"mean", "variance", "mode"}
    white_noise_reference(params)        {"mobility", "diffusivity", "variance"}
    first_moment(params, t, v0)          E[V(t) | V(0) = v0] [m/s]
    autocorrelation(params, t)           <V(t) V(0)> [m^2/s^2], stationary
    propagator(params, v, t, v0)         p(v, t | v0) [s/m], t > 0
    dry_friction_mobility(params), dry_friction_diffusivity(params),
    viscous_diffusivity(params)          closed-form limits
    white_noise(params, v0=, times=, velocities=)
                                         everything `stickslip analytic` prints
                                         (to_dict() is its JSON)
    FokkerPlanck(params, ...)            the solver, for repeated queries

Example: pure dry friction in nondimensional units, D = 5/4::

    p = stickslip.Params(friction=1, noise=1, tau=0, relaxation=float("inf"), bias=0)
    white_noise_reference(p)["diffusivity"]                     # 1.25
    first_moment(p, [0.05, 0.125, 0.25, 0.5, 1, 2.5], v0=1.0)   # Table I
"""

import numpy as _np

from . import _core
from ._commands import command

__all__ = [
    "hayakawa_density", "hayakawa_probability", "hayakawa_potential", "hayakawa_moments",
    "white_noise_reference", "first_moment", "autocorrelation", "propagator",
    "dry_friction_mobility", "dry_friction_diffusivity", "viscous_diffusivity", "is_pure_dry_friction",
    "white_noise", "FokkerPlanck", "WhiteNoiseResult",
]

FokkerPlanck = _core.FokkerPlanck
WhiteNoiseResult = _core.WhiteNoiseResult
FokkerPlanck.__module__ = WhiteNoiseResult.__module__ = __name__


def _check(params):
    if not isinstance(params, _core.Params):
        raise TypeError(f"params must be a stickslip.Params, got {type(params).__name__}")
    return params


def _broadcast(*xs):
    """Flat float64 copies of the broadcast arguments, and the shape to give back."""
    arrays = _np.broadcast_arrays(*[_np.asarray(x, dtype=float) for x in xs])
    shape = arrays[0].shape
    return [_np.ascontiguousarray(a).ravel() for a in arrays], shape


def _finite(values, what):
    """values, or UntrustworthyResultError (with them as .result) if any is not a
    finite number: the CLI refuses such a result (exit 3); a NaN returned quietly
    would pass for a number (analytic.first_moment at t = 1e23 gave nan)."""
    a = _np.asarray(values)
    if a.dtype.kind == "f" and not _np.all(_np.isfinite(a)):
        e = _core.UntrustworthyResultError(
            "the result's %s is not a finite number: the arguments take it beyond what double precision "
            "resolves" % what)
        e.result = values
        raise e
    return values


def _shaped(flat, shape):
    if shape == ():
        return float(flat[0])
    return flat.reshape(shape)


def hayakawa_density(params, v):
    """Hayakawa's normalised stationary density p(v) [s/m] at velocities v [m/s].

    p(v) ~ exp(-v^2/(noise*relaxation) - 2 friction |v|/noise + 2 bias v/noise);
    0 for |v| = inf. Normalised once per call (a millisecond of quadrature),
    then a few flops per value. Raises InvalidParameterError ("--bias: ...")
    when there is no stationary state (relaxation inf and |bias| >= friction).
    """
    (vv,), shape = _broadcast(v)
    return _shaped(_core._hayakawa_density(_check(params), vv), shape)


def hayakawa_probability(params, a, b):
    """P(a <= V <= b) under Hayakawa's density, a, b [m/s] (either may be infinite;
    a > b gives -P(b <= V <= a)). Exact to rounding (Gauss-Legendre panels split
    at the kink and the mode): use it to compare histogram bins."""
    (aa, bb), shape = _broadcast(a, b)
    return _shaped(_core._hayakawa_probability(_check(params), aa, bb), shape)


def hayakawa_potential(params, v):
    """phi(v) = -log(p(v)/p(mode)) >= 0 [dimensionless] at velocities v [m/s]."""
    (vv,), shape = _broadcast(v)
    return _shaped(_core._hayakawa_potential(_check(params), vv), shape)


def hayakawa_moments(params):
    """{"mean": E[V] = M0 [m/s], "variance": Var(V) [m^2/s^2], "mode": most probable v [m/s]}."""
    return _core._hayakawa_moments(_check(params))


def white_noise_reference(params):
    """Exact white-noise stationary quantities, by quadrature of Hayakawa's density:
    {"mobility": M0 [m/s], "diffusivity": D [m^2/s], "variance": Var(V) [m^2/s^2]}.

    M0 = int v p dv, F(v) = int_{-inf}^v (u - M0) p(u) du, D = (4/noise) int F^2/p dv.
    Any drift (relaxation, bias); params.tau is ignored. For pure dry friction
    in nondimensional units D = 5/4."""
    return _core._white_noise_reference(_check(params))


def is_pure_dry_friction(params):
    """True when relaxation is inf and bias is 0: the transient closed forms apply."""
    return _core._is_pure_dry_friction(_check(params))


def dry_friction_mobility(params):
    """(noise/friction) g/(1 - g^2) [m/s], g = bias/friction: white noise, no drag (relaxation inf)."""
    return _core._dry_friction_mobility(_check(params))


def dry_friction_diffusivity(params):
    """noise^3/friction^4 (5g^4 + 22g^2 + 5)/(4(1 - g^2)^4) [m^2/s], g = bias/friction: white noise,
    no drag (relaxation inf)."""
    return _core._dry_friction_diffusivity(_check(params))


def viscous_diffusivity(params):
    """relaxation^2 * noise [m^2/s]: the purely viscous (friction -> 0) limit."""
    return _core._viscous_diffusivity(_check(params))


def _solver(params):
    return _core.FokkerPlanck(params)


def first_moment(params, t, v0=0.0):
    """E[V(t) | V(0) = v0] [m/s] at times t >= 0 [s] from v0 [m/s] (t and v0 broadcast).

    Pure dry friction (relaxation inf, bias 0): Touchette et al.'s closed form
    (2.11). Otherwise: the Fokker-Planck solution (one solve per distinct v0;
    accurate to about 1e-6 relative, see fokker_planck.hpp)."""
    _check(params)
    (tt, vv), shape = _broadcast(t, v0)
    if _core._is_pure_dry_friction(params):
        return _finite(_shaped(_core._first_moment(params, tt, vv), shape), "first moment")
    fp = _solver(params)
    out = _np.empty_like(tt)
    for v in _np.unique(vv):
        idx = _np.nonzero(vv == v)[0]
        out[idx] = fp.first_moment(float(v), tt[idx])
    return _finite(_shaped(out, shape), "first moment")


def autocorrelation(params, t):
    """Stationary autocorrelation <V(t) V(0)> [m^2/s^2] at lags t [s] (even in t).

    Pure dry friction: closed form (2.13) (then C(0) = Var(V) and
    2 int_0^inf C = D); otherwise the Fokker-Planck solution (lags t >= 0; it
    tends to M0^2, not 0)."""
    _check(params)
    (tt,), shape = _broadcast(t)
    if _core._is_pure_dry_friction(params):
        return _finite(_shaped(_core._autocorrelation(params, tt), shape), "autocorrelation")
    return _finite(_shaped(_solver(params).autocorrelation(tt), shape), "autocorrelation")


def propagator(params, v, t, v0):
    """Transition density p(v, t | v0) [s/m] of V(t) = v [m/s] given V(0) = v0 [m/s], t > 0 [s].

    v, t and v0 broadcast. Pure dry friction: closed form (2.10); otherwise the
    Fokker-Planck solution (one solve per distinct v0)."""
    _check(params)
    (vv, tt, ww), shape = _broadcast(v, t, v0)
    if _core._is_pure_dry_friction(params):
        return _finite(_shaped(_core._propagator(params, vv, tt, ww), shape), "propagator")
    fp = _solver(params)
    out = _np.empty_like(vv)
    for w in _np.unique(ww):
        idx = _np.nonzero(ww == w)[0]
        ts, t_index = _np.unique(tt[idx], return_inverse=True)
        vs, v_index = _np.unique(vv[idx], return_inverse=True)
        table = fp.density(float(w), ts, vs)  # (times, velocities)
        out[idx] = table[t_index, v_index]
    return _finite(_shaped(out, shape), "propagator")


white_noise = command("white_noise", _core.WhiteNoiseRequest, """\
Every exact white-noise reference for one parameter set: what ``stickslip analytic`` prints.

    M0, D and Var(V) by quadrature of Hayakawa's density for any drift; with
    times, E[V(t)|v0] and <V(t)V(0)> (closed forms for pure dry friction, a
    Fokker-Planck solution otherwise); with velocities, the stationary density
    p(v) and the transition density p(v, t | v0).""", """\
    WhiteNoiseResult
        .mobility, .diffusivity, .variance (floats); .times (n,);
        .first_moment, .autocorrelation (EstimateSeries (n,): kind 'exact'
        for the closed forms, 'solved' with the grid's error otherwise, as
        the sampled moments' and correlation's); .velocities,
        .stationary_density (m,);
        .transient_density (n, m) (NaN rows at t = 0); .method; .meta;
        .to_dict() is the CLI's JSON; .to_columns() and .to_dataframe()
        give one row per (time, velocity) pair.""", params_doc="""\
    params : Params
        friction, noise, relaxation, bias (tau is not used).""", module="stickslip.analytic")
white_noise.__module__ = __name__
