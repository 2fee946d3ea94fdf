# SPDX-License-Identifier: BSD-3-Clause
"""Every class the package exports pickles (multiprocessing, joblib, caches):
a round trip gives an equal object, every number bit for bit, the same
warnings and meta; a pool of processes gives the numbers of a direct call."""
import math
import multiprocessing
import os
import pickle
import struct
import tempfile
import unittest
import warnings

import numpy as np

import stickslip
import stickslip.analytic
from _support import without_work

# Exported classes that hold no value to pickle: the exceptions, and the
# Fokker-Planck solver (its factorised grids are remade from Params).
NOT_PICKLED = {"FokkerPlanck"}

SMALL = dict(excursions=200, scheme="resolvent", dt=1e-3, seed=5)


def exported_classes():
    """{name: class} of everything `stickslip` and `stickslip.analytic` export."""
    out = {}
    for module in (stickslip, stickslip.analytic):
        for name in module.__all__:
            obj = getattr(module, name)
            if isinstance(obj, type) and not issubclass(obj, BaseException) and name not in NOT_PICKLED:
                out[name] = obj
    return out


def examples():
    """{class name: [instances]}: small runs covering the optional parts of
    the results (a solved result, the PDMP, the discretisation checks, a drift
    law, densities per time, excursion and path trajectories)."""
    p = stickslip.Params()
    law = stickslip.Params(drift=lambda v: 0.342 - v / 0.067, knots=65)
    d = stickslip.diffusivity(p, **SMALL)
    density = stickslip.density(p, bins=6, **SMALL)
    sweep = stickslip.sweep(p, noise=[4, 5, 6], tau=[0.5, 1], excursions=64)
    white_sweep = stickslip.sweep(p, noise=[5], tau=[1e-3, 3e-3, 1e-2, 3e-2], engine="kolmogorov", rel_precision=1e-2)
    solved_sweep = stickslip.sweep(p, noise=[4, 5], tau=[0.5], engine="kolmogorov", rel_precision=1e-2)
    moments = stickslip.moments(p, scheme="resolvent", dt=1e-3, trajectories=100, times=[0.1, 0.3], density=True,
                                bins=4)
    trajectory = stickslip.trajectory(p, scheme="resolvent", dt=1e-2, paths=2, time=1, every=0.25)
    request = stickslip.DiffusivityRequest()
    request.set("excursions", 300)
    request.params = law
    return {
        "Params": [p, law, stickslip.Params(drift="0.342 - v/0.067", tau=0), stickslip.Params(relaxation=math.inf)],
        "Scales": [p.scales()],
        "Estimate": [d.diffusivity],
        "GridEstimate": [stickslip.diffusivity(p, engine="kolmogorov", rel_precision=1e-2).diffusivity],
        "EstimateSeries": [density.density, sweep.diffusivity],
        "GridEstimateSeries": [solved_sweep.diffusivity],  # another name of EstimateSeries
        "Histogram": [density.histogram, moments.density[1]],
        "Path": [trajectory.paths[1]],
        "SweepExponent": [sweep.exponents[0]],
        "SweepWhiteLimit": [white_sweep.white_limits[0]],
        "DiffusivityResult": [
            d,
            stickslip.diffusivity(p, engine="kolmogorov", rel_precision=1e-2),
            stickslip.diffusivity(p, engine="pdmp", excursions=200, seed=2),
            stickslip.diffusivity(p, check_dt=True, control_variate="off", **SMALL),
            stickslip.diffusivity(law, check_knots=True, **SMALL),
        ],
        "BruteForceResult": [stickslip.bruteforce(p, scheme="resolvent", dt=1e-3, time=1, trajectories=100)],
        "DensityResult": [density],
        "CorrelationResult": [stickslip.correlation(p, lags=4, **SMALL)],
        "MomentsResult": [moments],
        "TrajectoryResult": [trajectory, stickslip.trajectory(p, scheme="resolvent", dt=1e-3)],
        "SweepResult": [sweep, solved_sweep, white_sweep],
        "WhiteNoiseResult": [stickslip.analytic.white_noise(p.replace(bias=0.2), times=[0, 0.5], v0=0.5,
                                                            velocities=[-0.5, 0.25, 1])],
        "SpectrumResult": [
            stickslip.spectrum(p, frequencies=[0, 1], rel_precision=0.05),
            stickslip.spectrum(p.replace(tau=0, relaxation=math.inf), frequencies=[0, 0.5]),
            stickslip.spectrum(p.replace(tau=0), frequencies=[0, 0.5]),  # with drag: the Fokker-Planck chain
            stickslip.spectrum(p, engine="pdmp", excursions=50, sample_dt=0.01, frequencies=[0, 0.5]),
        ],
        "DiffusivityRequest": [request],
        "BruteForceRequest": [stickslip.BruteForceRequest()],
        "DensityRequest": [stickslip.DensityRequest()],
        "CorrelationRequest": [stickslip.CorrelationRequest()],
        "MomentsRequest": [stickslip.MomentsRequest()],
        "TrajectoryRequest": [stickslip.TrajectoryRequest()],
        "SweepRequest": [stickslip.SweepRequest()],
        "WhiteNoiseRequest": [stickslip._core.WhiteNoiseRequest()],
        "SpectrumRequest": [stickslip.SpectrumRequest()],
    }


def bits(x):
    return struct.pack("<d", x)


class Same:
    """Asserts two values equal bit for bit: floats by their bits (NaN too),
    arrays by dtype, shape and bytes, the package's objects by every property."""

    def __init__(self, test):
        self.test = test

    def __call__(self, a, b, where):
        t = self.test
        t.assertIs(type(a), type(b), where)
        if isinstance(a, float):
            t.assertEqual(bits(a), bits(b), where)
        elif isinstance(a, np.ndarray):
            t.assertEqual((a.dtype, a.shape), (b.dtype, b.shape), where)
            t.assertEqual(a.tobytes(), b.tobytes(), where)
        elif isinstance(a, (list, tuple)):
            t.assertEqual(len(a), len(b), where)
            for k, (x, y) in enumerate(zip(a, b)):
                self(x, y, f"{where}[{k}]")
        elif isinstance(a, dict):
            t.assertEqual(list(a), list(b), where)
            for k in a:
                self(a[k], b[k], f"{where}[{k!r}]")
        elif type(a).__module__.startswith("stickslip"):
            for name in dir(type(a)):
                if name.startswith("_") or not isinstance(getattr(type(a), name), property):
                    continue
                try:
                    x = getattr(a, name)
                except Exception as e:  # e.g. a solved result has no sample count: the copy neither
                    with t.assertRaises(type(e), msg=f"{where}.{name}"):
                        getattr(b, name)
                    continue
                self(x, getattr(b, name), f"{where}.{name}")
        else:
            t.assertEqual(a, b, where)


def round_trip(x):
    return pickle.loads(pickle.dumps(x, protocol=pickle.HIGHEST_PROTOCOL))


class RoundTrip(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", stickslip.StickslipWarning)
            cls.examples = examples()

    def test_every_exported_class_pickles(self):
        classes = exported_classes()
        # A class exported without an example here (a new result type) fails:
        # give it one, and pickling (python/src/pickling.cpp).
        self.assertEqual(sorted(set(classes) - set(self.examples)), [])
        same = Same(self)
        for name, instances in self.examples.items():
            for k, x in enumerate(instances):
                with self.subTest(cls=name, example=k):
                    self.assertIs(type(x), classes.get(name, type(x)))
                    y = round_trip(x)
                    same(x, y, name)
                    if " object at 0x" not in repr(x):
                        self.assertEqual(repr(y), repr(x))
                    if hasattr(x, "settings"):  # a request: every setting
                        for setting in x.settings():
                            same(x.get(setting["keyword"]), y.get(setting["keyword"]), setting["keyword"])
                    for method in ("to_json", "to_csv", "to_table"):  # the CLI's renderings, timing included
                        if hasattr(x, method):
                            self.assertEqual(getattr(y, method)(), getattr(x, method)(), method)
                    for method in ("to_dict", "to_columns"):
                        if hasattr(x, method):
                            same(getattr(x, method)(), getattr(y, method)(), f"{name}.{method}()")
                    if hasattr(x, "meta"):
                        self.assertEqual(y.meta, x.meta)
                        self.assertEqual(y.warnings, x.warnings)

    def test_the_notes_survive(self):
        r = self.examples["DiffusivityResult"][3]
        self.assertTrue(r.warnings)  # --check-dt without the control variate's pilot: notes
        self.assertEqual(round_trip(r).warnings, r.warnings)

    def test_a_request_runs_the_same_after_a_round_trip(self):
        request = self.examples["DiffusivityRequest"][0]
        copy = round_trip(request)
        self.assertEqual(copy.params.drift, request.params.drift)  # the law's knots, exactly
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", stickslip.StickslipWarning)
            a, b = stickslip.run(request), stickslip.run(copy)
        self.assertEqual(without_work(b.to_dict()), without_work(a.to_dict()))

    def test_another_version_is_refused(self):
        state = self.examples["Estimate"][0].__getstate__()
        self.assertEqual(state[0], stickslip.__version__)
        e = stickslip.Estimate.__new__(stickslip.Estimate)
        with self.assertRaisesRegex(ValueError, "written by stickslip 0.0.0-other"):
            e.__setstate__(("0.0.0-other", state[1]))
        with self.assertRaisesRegex(ValueError, "cannot unpickle"):
            e.__setstate__((stickslip.__version__, state[1][:-1]))


def _diffusivity(params_and_seed):  # a worker's job (module level: a spawned process imports it)
    params, seed = params_and_seed
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", stickslip.StickslipWarning)
        return stickslip.diffusivity(params, excursions=200, scheme="resolvent", dt=1e-3, seed=seed, threads=1)


class Processes(unittest.TestCase):
    def test_a_pool_gives_the_numbers_of_a_direct_call(self):
        jobs = [(stickslip.Params(noise=noise), seed) for noise, seed in ((5, 1), (4, 2), (6, 3))]
        # spawn: fresh interpreters, as on macOS and Windows, so the results
        # (and the parameters sent) cross a process boundary as pickles only
        with multiprocessing.get_context("spawn").Pool(2) as pool:
            pooled = pool.map(_diffusivity, jobs)
        for job, r in zip(jobs, pooled):
            with self.subTest(job=job):
                direct = _diffusivity(job)
                for name in ("diffusivity", "mobility", "mean_duration"):
                    a, b = getattr(r, name), getattr(direct, name)
                    self.assertEqual([bits(x) for x in (a.value, a.stderr, a.lo, a.hi)],
                                     [bits(x) for x in (b.value, b.stderr, b.lo, b.hi)], name)
                self.assertEqual(without_work(r.to_dict()), without_work(direct.to_dict()))
                self.assertEqual(r.meta, direct.meta)
                self.assertEqual(r.warnings, direct.warnings)


class WhiteNoiseTable(unittest.TestCase):
    def setUp(self):
        self.p = stickslip.Params(bias=0.2)

    def test_columns_are_time_major_pairs(self):
        r = stickslip.analytic.white_noise(self.p, times=[0, 0.1, 1], v0=0.5, velocities=[-1, 0.5])
        cols = r.to_columns()
        self.assertEqual(list(cols), ["mobility", "diffusivity", "variance", "time", "first_moment",
                                      "first_moment_error", "autocorrelation", "autocorrelation_error", "v",
                                      "stationary_density", "transient_density"])
        self.assertTrue(all(c.shape == (6,) for c in cols.values()))
        np.testing.assert_array_equal(cols["time"], [0, 0, 0.1, 0.1, 1, 1])
        np.testing.assert_array_equal(cols["v"], [-1, 0.5] * 3)
        np.testing.assert_array_equal(cols["first_moment"], np.repeat(r.first_moment, 2))
        np.testing.assert_array_equal(cols["stationary_density"], np.tile(r.stationary_density, 3))
        np.testing.assert_array_equal(cols["transient_density"][2:], r.transient_density[1:].ravel())
        self.assertTrue(np.isnan(cols["transient_density"][:2]).all())  # t = 0: a delta function
        np.testing.assert_array_equal(cols["diffusivity"], np.full(6, r.diffusivity))

    def test_columns_without_velocities_are_the_csv_rows(self):
        r = stickslip.analytic.white_noise(self.p, times=[0.1, 1])
        cols = r.to_columns()
        body = [ln for ln in r.to_csv().splitlines() if not ln.startswith("#")]
        self.assertEqual(body[0].split(","), list(cols))
        for k, line in enumerate(body[1:]):
            self.assertEqual([float(x) for x in line.split(",")], [float(c[k]) for c in cols.values()])

    def test_stationary_values_alone_are_one_row(self):
        cols = stickslip.analytic.white_noise(self.p).to_columns()
        self.assertEqual({k: len(c) for k, c in cols.items()}, {"mobility": 1, "diffusivity": 1, "variance": 1})

    def test_npz_and_meta(self):
        r = stickslip.analytic.white_noise(self.p, times=[0.1, 1], velocities=[0.5])
        self.assertEqual(r.meta["settings"]["bias"], 0.2)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "w.npz")
            r.save(path)
            z = np.load(path)
            self.assertEqual(sorted(z.files), sorted(list(r.to_columns()) + ["meta"]))
            np.testing.assert_array_equal(z["transient_density"], r.to_columns()["transient_density"])

    @unittest.skipUnless(__import__("importlib").util.find_spec("pandas"), "pandas is not installed")
    def test_dataframe(self):
        r = stickslip.analytic.white_noise(self.p, times=[0, 0.1, 1], velocities=[-1, 0.5])
        frame = r.to_dataframe()
        self.assertEqual(frame.shape, (6, 9))
        self.assertEqual(list(frame.columns), list(r.to_columns()))
        self.assertEqual(frame.attrs["meta"], r.meta)


if __name__ == "__main__":
    unittest.main()
