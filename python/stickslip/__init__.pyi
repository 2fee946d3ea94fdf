# Type stubs of the stickslip package. SI units throughout (m, s); defaults are
# the paper's Fig. 2 case and the CLI's. See help(stickslip.<function>).
from typing import List, Literal, Mapping, Optional, Sequence, Tuple, Union

from . import analytic as analytic
from ._core import (
    BruteForceResult as BruteForceResult,
    CappedExcursionsError as CappedExcursionsError,
    CorrelationResult as CorrelationResult,
    DensityResult as DensityResult,
    DiffusivityResult as DiffusivityResult,
    Estimate as Estimate,
    EstimateSeries as EstimateSeries,
    Histogram as Histogram,
    InvalidParameterError as InvalidParameterError,
    MomentsResult as MomentsResult,
    Params as Params,
    Path as Path,
    Scales as Scales,
    SweepExponent as SweepExponent,
    SweepResult as SweepResult,
    TrajectoryResult as TrajectoryResult,
    __version__ as __version__,
)

import numpy.typing as npt

_ParamsLike = Union[Params, Mapping[str, float], None]
_Engine = Literal["inclusion", "pdmp"]
_StopRule = Literal["auto", "bridge", "stuck"]
_Estimator = Literal["renewal", "paper"]
_Numbers = Union[Sequence[float], npt.NDArray]

def logspace(lo: float, hi: float, n: int) -> List[float]: ...

def diffusivity(params: _ParamsLike = None, *, excursions: int = 10000, engine: _Engine = "inclusion",
                dt: float = 1e-4, grid: float = 0.125, stop_rule: _StopRule = "auto",
                estimator: _Estimator = "renewal", allow_capped: bool = False, seed: int = 1, threads: int = 0,
                level: float = 0.95, progress: bool = False, lattice_bound: float = 0.0, white_level: float = 0.0,
                max_steps: int = 200_000_000, rel_precision: float = 0.0,
                max_excursions: int = 100_000_000) -> DiffusivityResult: ...

def bruteforce(params: _ParamsLike = None, *, time: float = 10.0, trajectories: int = 1000,
               x0: Optional[float] = None, v0: float = 0.0, engine: _Engine = "inclusion", dt: float = 1e-4,
               grid: float = 0.125, stop_rule: _StopRule = "auto", seed: int = 1, threads: int = 0,
               level: float = 0.95, progress: bool = False, lattice_bound: float = 0.0, white_level: float = 0.0,
               max_steps: int = 200_000_000) -> BruteForceResult: ...

def density(params: _ParamsLike = None, *, excursions: int = 10000, bins: int = 80,
            range: Optional[Tuple[float, float]] = None, sample_dt: float = 0.0, engine: _Engine = "inclusion",
            dt: float = 1e-4, grid: float = 0.125, stop_rule: _StopRule = "auto", allow_capped: bool = False,
            seed: int = 1, threads: int = 0, level: float = 0.95, progress: bool = False,
            lattice_bound: float = 0.0, white_level: float = 0.0, max_steps: int = 200_000_000) -> DensityResult: ...

def correlation(params: _ParamsLike = None, *, excursions: int = 10000, max_lag: float = 0.0, lags: int = 50,
                sample_dt: float = 0.0, engine: _Engine = "inclusion", dt: float = 1e-4, grid: float = 0.125,
                stop_rule: _StopRule = "auto", allow_capped: bool = False, seed: int = 1, threads: int = 0,
                level: float = 0.95, progress: bool = False, lattice_bound: float = 0.0, white_level: float = 0.0,
                max_steps: int = 200_000_000) -> CorrelationResult: ...

def moments(params: _ParamsLike = None, *, times: Optional[_Numbers] = None, v0: Optional[float] = None,
            x0: Optional[float] = None, trajectories: int = 10000, density: bool = False, bins: int = 60,
            range: Optional[Tuple[float, float]] = None, engine: _Engine = "inclusion", dt: float = 1e-4,
            grid: float = 0.125, stop_rule: _StopRule = "auto", seed: int = 1, threads: int = 0,
            level: float = 0.95, progress: bool = False, lattice_bound: float = 0.0, white_level: float = 0.0,
            max_steps: int = 200_000_000) -> MomentsResult: ...

def trajectory(params: _ParamsLike = None, *, index: int = 0, paths: int = 0, time: float = 2.0,
               x0: Optional[float] = None, v0: float = 0.0, every: float = 0.0, max_points: int = 5_000_000,
               engine: _Engine = "inclusion", dt: float = 1e-4, grid: float = 0.125, stop_rule: _StopRule = "auto",
               seed: int = 1, threads: int = 0, progress: bool = False, lattice_bound: float = 0.0,
               white_level: float = 0.0, max_steps: int = 200_000_000) -> TrajectoryResult: ...

def sweep(params: _ParamsLike = None, *, noise: Optional[_Numbers] = None, tau: Optional[_Numbers] = None,
          excursions: int = 10000, engine: _Engine = "inclusion", dt: float = 1e-4, grid: float = 0.125,
          stop_rule: _StopRule = "auto", estimator: _Estimator = "renewal", allow_capped: bool = False,
          seed: int = 1, threads: int = 0, level: float = 0.95, progress: bool = False,
          lattice_bound: float = 0.0, white_level: float = 0.0, max_steps: int = 200_000_000) -> SweepResult: ...
