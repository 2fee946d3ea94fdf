# SPDX-License-Identifier: BSD-3-Clause
# Type stubs of the compiled part of stickslip. Units are SI (m, s); see the
# docstrings (help(stickslip.Params), ...) for the model and conventions.
# Written by hand, except the classes of results that declare their fields
# (SweepExponent, SweepWhiteLimit, ...), which python/tools/make_stubs.py
# rewrites from the declarations (result_fields.hpp).
from typing import Any, Callable, Dict, List, Literal, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

# Every class below but FokkerPlanck pickles (pickle, multiprocessing, joblib):
# an equal object, bit for bit; the format is not stable across versions.

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

class InvalidParameterError(ValueError):
    """str(e) == '--<parameter>: <message>', the CLI's error text."""
    parameter: str
    message: str

class UntrustworthyResultError(RuntimeError): ...

class CappedExcursionsError(UntrustworthyResultError): ...

class Scales:
    @property
    def time(self) -> float: ...  # [s]
    @property
    def length(self) -> float: ...  # [m]
    @property
    def velocity(self) -> float: ...  # [m/s]
    @property
    def acceleration(self) -> float: ...  # [m s^-2]
    @property
    def diffusivity(self) -> float: ...  # [m^2/s]
    @property
    def noise_level(self) -> float: ...  # [s^-1/2]
    def to_dict(self) -> dict[str, float]: ...

class Params:
    def __init__(self, *, friction: float = 3.84, noise: float = 5.0, tau: float = 0.5,
                 relaxation: float = 0.067, bias: float = 0.342, static_friction: float | None = None,
                 drift: str | Callable[[float], float] | tuple[npt.ArrayLike, npt.ArrayLike] | None = None,
                 drift_params: str = "", drift_table: str = "", knots: int = 1025) -> None: ...
    @property
    def friction(self) -> float: ...      # Delta [m s^-2], > 0
    @property
    def noise(self) -> float: ...         # Gamma [m^2 s^-3], > 0
    @property
    def tau(self) -> float: ...           # [s], >= 0; 0 = white noise
    @property
    def relaxation(self) -> float: ...    # [s], > 0 or inf (no drag)
    @property
    def bias(self) -> float: ...          # [m s^-2]
    @property
    def static_friction(self) -> float | None: ...  # Delta_s [m s^-2] >= friction; None: equal to friction
    @property
    def drift(self) -> str | tuple[list[float], list[float]] | None: ...  # b(v), when not affine
    @property
    def knots(self) -> int: ...           # knots of a drift law's interpolant
    @property
    def force_amplitude(self) -> float: ...  # sqrt(noise/2)
    @property
    def white(self) -> bool: ...
    @property
    def upper_threshold(self) -> float: ...  # x* [s^-1/2]
    @property
    def lower_threshold(self) -> float: ...  # x-* [s^-1/2]
    @property
    def has_stationary_state(self) -> bool: ...
    def nondimensional(self) -> Params: ...
    def scales(self) -> Scales: ...
    @staticmethod
    def from_nondimensional(nd: Params, friction: float, noise: float) -> Params: ...
    def replace(self, **changes: float) -> Params: ...
    def to_dict(self) -> dict[str, float]: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

class Estimate:  # every method's: kind says what error is
    @property
    def value(self) -> float: ...
    @property
    def stderr(self) -> float: ...  # the standard error; NaN unless kind == 'sampled'
    @property
    def error(self) -> float: ...   # standard error, discretisation error or 0, by kind
    @property
    def kind(self) -> Literal['sampled', 'solved', 'exact']: ...
    @property
    def lo(self) -> float: ...      # NaN unless sampled
    @property
    def hi(self) -> float: ...
    @property
    def level(self) -> float: ...
    @property
    def ci(self) -> Tuple[float, float]: ...
    def to_dict(self) -> dict[str, Any]: ...
    def __float__(self) -> float: ...

GridEstimate = Estimate  # the Kolmogorov engine's values (kind 'solved'); the name before estimates had kinds

class EstimateSeries:
    @property
    def shape(self) -> Tuple[int, ...]: ...  # (n,), or (n_tau, n_noise) for a sweep
    @property
    def value(self) -> FloatArray: ...   # (n,); a sweep: (n_tau, n_noise)
    @property
    def stderr(self) -> FloatArray: ...  # (n,): NaN unless kind is 'sampled'
    @property
    def error(self) -> FloatArray: ...   # (n,): standard errors (sampled) or discretisation errors (solved)
    @property
    def kind(self) -> str: ...           # 'sampled' or 'solved'
    @property
    def lo(self) -> FloatArray: ...      # (n,)
    @property
    def hi(self) -> FloatArray: ...      # (n,)
    @property
    def ci(self) -> FloatArray: ...      # (n, 2); a sweep: (n_tau, n_noise, 2)
    @property
    def level(self) -> float: ...
    def __len__(self) -> int: ...
    def __getitem__(self, k: int) -> Estimate: ...
    def __array__(self, dtype: Any = ...) -> FloatArray: ...
    def to_dict(self) -> dict[str, Any]: ...

GridEstimateSeries = EstimateSeries  # a solved series (kind 'solved'); the name before estimates had kinds

class Histogram:
    @property
    def edges(self) -> FloatArray: ...  # [m/s]
    @property
    def bins(self) -> EstimateSeries: ...  # [s/m]
    @property
    def below(self) -> Estimate: ...
    @property
    def above(self) -> Estimate: ...
    @property
    def stuck_probability(self) -> Estimate: ...
    @property
    def time(self) -> float: ...  # [s]
    @property
    def centers(self) -> FloatArray: ...  # (bins,) [m/s]
    @property
    def widths(self) -> FloatArray: ...   # (bins,) [m/s]
    @property
    def density(self) -> EstimateSeries: ...  # (bins,) [s/m], V = 0 excluded

class Path:
    @property
    def t(self) -> FloatArray: ...   # [s]
    @property
    def x(self) -> FloatArray: ...   # noise X [s^-1/2]
    @property
    def mode(self) -> IntArray: ...  # -1 / 0 / +1
    @property
    def v(self) -> FloatArray: ...   # [m/s]
    @property
    def u(self) -> FloatArray: ...   # [m]
    def __len__(self) -> int: ...
    def to_dict(self) -> dict[str, npt.NDArray[Any]]: ...

class _Rendered:
    @property
    def warnings(self) -> List[str]: ...
    @property
    def params(self) -> Params: ...
    def to_json(self, indent: int = 2) -> str: ...
    def to_dict(self) -> dict[str, Any]: ...
    def to_table(self) -> str: ...
    def to_csv(self) -> str: ...  # '#' lines of provenance, a header, the rows
    @property
    def meta(self) -> dict[str, Any]: ...  # {'command', 'settings', 'version', 'revision'}
    # Added by the package (stickslip/_tables.py):
    def to_columns(self) -> dict[str, npt.NDArray[Any]]: ...  # one row per point or bin
    def to_dataframe(self) -> Any: ...  # pandas.DataFrame of to_columns(); ImportError without pandas
    def to_npz(self, path: str) -> None: ...  # to_columns() and meta, atomically
    def save(self, path: str) -> None: ...  # .npz, .json, .csv or .txt, atomically

class _Totals(_Rendered):
    @property
    def capped(self) -> int: ...
    @property
    def work(self) -> int: ...
    @property
    def seconds(self) -> float: ...  # [s]
    @property
    def threads_from(self) -> str: ...
    @property
    def resumed(self) -> int: ...
    @property
    def threads(self) -> int: ...
    @property
    def interrupted(self) -> bool: ...

class _LongExcursions(_Totals):
    @property
    def diffusivity(self) -> Estimate: ...  # [m^2/s]
    @property
    def mobility(self) -> Estimate: ...  # [m/s]
    @property
    def mean_duration(self) -> Estimate: ...  # [s]
    @property
    def completed(self) -> int: ...
    @property
    def estimator(self) -> str: ...

class DiffusivityResult(_LongExcursions):
    @property
    def diffusivity(self) -> Union[Estimate, GridEstimate]: ...  # type: ignore[override]  # D [m^2/s]
    @property
    def mobility(self) -> Union[Estimate, GridEstimate]: ...  # type: ignore[override]  # M0 [m/s]
    @property
    def stuck_probability(self) -> Optional[GridEstimate]: ...  # P(V = 0), engine="kolmogorov"
    @property
    def mean_duration(self) -> Union[Estimate, GridEstimate]: ...  # type: ignore[override]  # E[t1] [s]
    @property
    def method(self) -> str: ...  # "monte carlo" or "kolmogorov"
    @property
    def precision(self) -> Optional[Dict[str, Any]]: ...
    @property
    def discretisation(self) -> Optional[Dict[str, Any]]: ...
    @property
    def engine(self) -> str: ...
    @property
    def estimator(self) -> str: ...
    @property
    def stop_rule(self) -> str: ...
    @property
    def excursions(self) -> int: ...
    @property
    def seed(self) -> int: ...
    @property
    def level(self) -> float: ...

class BruteForceResult(_Totals):
    @property
    def diffusivity(self) -> Estimate: ...  # D_t [m^2/s]
    @property
    def mobility(self) -> Estimate: ...     # U(t)/t [m/s]
    @property
    def trajectories(self) -> int: ...
    @property
    def time(self) -> float: ...
    @property
    def x0(self) -> float: ...
    @property
    def v0(self) -> float: ...
    @property
    def engine(self) -> str: ...

class DensityResult(_LongExcursions):
    @property
    def mean(self) -> Estimate: ...  # [m/s]
    @property
    def variance(self) -> Estimate: ...  # [m^2/s^2]
    @property
    def histogram(self) -> Histogram: ...
    @property
    def edges(self) -> FloatArray: ...
    @property
    def centers(self) -> FloatArray: ...
    @property
    def density(self) -> Union[EstimateSeries, FloatArray]: ...  # FloatArray with engine="kolmogorov"
    @property
    def stuck_probability(self) -> Union[Estimate, GridEstimate]: ...  # GridEstimate with engine="kolmogorov"
    @property
    def diffusivity(self) -> Union[Estimate, GridEstimate]: ...  # type: ignore[override]
    @property
    def mobility(self) -> Union[Estimate, GridEstimate]: ...  # type: ignore[override]
    @property
    def below(self) -> Estimate: ...
    @property
    def above(self) -> Estimate: ...

class CorrelationResult(_LongExcursions):
    @property
    def lag(self) -> FloatArray: ...  # [s]
    @property
    def autocorrelation(self) -> EstimateSeries: ...  # [m^2/s^2]
    @property
    def covariance(self) -> EstimateSeries: ...  # [m^2/s^2]
    @property
    def normalised_covariance(self) -> EstimateSeries: ...
    @property
    def mean(self) -> Estimate: ...  # [m/s]
    @property
    def normalised(self) -> EstimateSeries: ...

class MomentsResult(_Totals):
    @property
    def time(self) -> FloatArray: ...  # [s]
    @property
    def first_moment(self) -> EstimateSeries: ...  # [m/s]
    @property
    def second_moment(self) -> EstimateSeries: ...  # [m^2/s^2]
    @property
    def stuck_probability(self) -> EstimateSeries: ...
    @property
    def density(self) -> List[Histogram]: ...
    @property
    def v0(self) -> float: ...
    @property
    def trajectories(self) -> int: ...

class TrajectoryResult(_Rendered):
    @property
    def displacement(self) -> float: ...  # [m]
    @property
    def duration(self) -> float: ...  # [s]
    @property
    def first_half_duration(self) -> float: ...  # [s]
    @property
    def complete(self) -> bool: ...
    @property
    def work(self) -> int: ...
    @property
    def paths(self) -> List[Path]: ...
    @property
    def path(self) -> Path: ...

class SweepExponent:
    @property
    def varied(self) -> float: ...
    @property
    def tau(self) -> float: ...  # [s]
    @property
    def exponent(self) -> Estimate: ...
    @property
    def chi2_per_dof(self) -> float: ...
    @property
    def points(self) -> int: ...

class SweepWhiteLimit:
    @property
    def varied(self) -> float: ...
    @property
    def noise(self) -> float: ...  # [m^2 s^-3]
    @property
    def white_diffusivity(self) -> float: ...  # [m^2/s]
    @property
    def exponent(self) -> Estimate: ...
    @property
    def coefficient(self) -> Estimate: ...
    @property
    def chi2_per_dof(self) -> float: ...
    @property
    def half_order(self) -> Estimate: ...
    @property
    def first_order(self) -> Estimate: ...
    @property
    def three_half_order(self) -> Estimate: ...
    @property
    def points(self) -> int: ...
    @property
    def tau_within_percent(self) -> float: ...  # [s]

class SweepResult(_Rendered):
    @property
    def noises(self) -> FloatArray: ...
    @property
    def taus(self) -> FloatArray: ...
    @property
    def shape(self) -> Tuple[int, int]: ...
    @property
    def noise(self) -> FloatArray: ...  # (n_tau, n_noise)
    @property
    def tau(self) -> FloatArray: ...  # (n_tau, n_noise)
    @property
    def diffusivity(self) -> EstimateSeries: ...  # kind 'solved' with engine="kolmogorov"
    @property
    def mobility(self) -> EstimateSeries: ...
    @property
    def mean_duration(self) -> EstimateSeries: ...
    @property
    def stuck_probability(self) -> Optional[EstimateSeries]: ...  # P(V = 0), engine="kolmogorov"
    @property
    def slope(self) -> EstimateSeries: ...
    @property
    def white_ratio(self) -> EstimateSeries: ...  # D / D_white
    @property
    def method(self) -> str: ...  # "monte carlo" or "kolmogorov"
    @property
    def stop_rule(self) -> List[str]: ...
    @property
    def exponents(self) -> List[SweepExponent]: ...
    @property
    def white_limits(self) -> List[SweepWhiteLimit]: ...
    @property
    def seconds(self) -> float: ...
    @property
    def interrupted(self) -> bool: ...
    @property
    def resumed(self) -> int: ...

class WhiteNoiseResult(_Rendered):
    @property
    def time(self) -> FloatArray: ...  # [s]
    @property
    def first_moment(self) -> EstimateSeries: ...  # [m/s]
    @property
    def autocorrelation(self) -> EstimateSeries: ...  # [m^2/s^2]
    @property
    def mobility(self) -> float: ...  # [m/s]
    @property
    def diffusivity(self) -> float: ...  # [m^2/s]
    @property
    def variance(self) -> float: ...  # [m^2/s^2]
    @property
    def times(self) -> FloatArray: ...
    @property
    def v0(self) -> float: ...
    @property
    def velocities(self) -> FloatArray: ...
    @property
    def stationary_density(self) -> FloatArray: ...
    @property
    def transient_density(self) -> FloatArray: ...  # (times, velocities)
    @property
    def method(self) -> str: ...

class SpectrumResult(_Rendered):
    @property
    def frequency(self) -> FloatArray: ...  # [rad/s]
    @property
    def spectrum(self) -> EstimateSeries: ...  # [m^2/s]
    @property
    def params(self) -> Params: ...
    @property
    def diffusivity(self) -> Estimate: ...  # [m^2/s], S(0)
    @property
    def mobility(self) -> Estimate: ...  # [m/s]
    @property
    def method(self) -> str: ...

class FokkerPlanck:  # not picklable: make it again from its Params
    def __init__(self, params: Params, cells: int = 4000, half_width: float = 0.0,
                 steps_per_unit_time: int = 1000, richardson: bool = True) -> None: ...
    def first_moment(self, v0: float, t: npt.ArrayLike) -> FloatArray: ...
    def autocorrelation(self, t: npt.ArrayLike) -> FloatArray: ...
    def density(self, v0: float, t: npt.ArrayLike, v: npt.ArrayLike) -> FloatArray: ...
    @property
    def cell_width(self) -> float: ...
    @property
    def lower_velocity(self) -> float: ...
    @property
    def upper_velocity(self) -> float: ...

class _Request:
    """The settings of one computation (DiffusivityRequest, ...): every setting
    at its default (the CLI's) until set()."""
    def __init__(self) -> None: ...
    def set(self, keyword: str, value: Any) -> None: ...
    def get(self, keyword: str) -> Any: ...
    params: Params
    command: str  # what asks for the run, as its JSON and CSV record it ('' records null)
    def validate(self) -> None: ...
    @staticmethod
    def settings() -> List[Dict[str, Any]]: ...
    resumable: bool

class DiffusivityRequest(_Request): ...
class BruteForceRequest(_Request): ...
class DensityRequest(_Request): ...
class CorrelationRequest(_Request): ...
class MomentsRequest(_Request): ...
class TrajectoryRequest(_Request): ...
class SweepRequest(_Request): ...
class WhiteNoiseRequest(_Request): ...
class SpectrumRequest(_Request): ...

def run(
    request: _Request,
    progress: bool = False,
    checkpoint: Optional[str] = None,
    checkpoint_every: float = 60.0,
    resume: Optional[str] = None,
) -> Any: ...

keyword_of_flag: Dict[str, str]  # "--max-steps" -> "max_steps", for every setting
def python_text(note: str) -> str: ...
def write_output_file(path: str, data: bytes) -> None: ...

checkpoint_help: Dict[str, str]
checkpoint_every_default: float
