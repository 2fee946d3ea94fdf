// Simulations from Python: the compute functions of diffusivity.hpp,
// observables.hpp and sweep.hpp, run off the Python thread with the GIL
// released, interruptible by Ctrl-C, and their result classes.
//
// Interruption: the library reports progress through RunControl::progress,
// called from whichever worker thread merges a block, and stops the run
// (RunCancelled) when it returns false. Python runs signal handlers only in
// its main thread, so the computation runs on a helper thread while the
// calling thread waits, waking every 50 ms to take the GIL and call
// PyErr_CheckSignals(). When a handler raises (KeyboardInterrupt), the flag
// the progress callback reads is set, the run stops after the current block,
// and the pending Python exception is re-raised.
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <future>
#include <limits>
#include <mutex>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/observables.hpp"
#include "stickslip/report.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::python {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Shared between the computation (progress callbacks, any thread) and the
/// waiting Python thread.
struct Monitor {
    std::atomic<bool> cancel{false};
    std::mutex mutex;
    std::uint64_t done = 0, total = 0;
    double seconds = 0;
    std::string label;
    bool seen = false;

    std::function<bool(const Progress&)> callback(std::string what) {
        return [this, what = std::move(what)](const Progress& p) {
            {
                std::lock_guard<std::mutex> lock(mutex);
                done = p.done;
                total = p.total;
                seconds = p.seconds;
                label = what;
                seen = true;
            }
            return !cancel.load();
        };
    }

    /// One progress line on sys.stderr (needs the GIL). Errors are ignored.
    void print(bool final) {
        std::uint64_t d, t;
        double s;
        std::string what;
        {
            std::lock_guard<std::mutex> lock(mutex);
            if (!seen) return;
            d = done;
            t = total;
            s = seconds;
            what = label;
        }
        const double rate = s > 0 ? static_cast<double>(d) / s : 0.0;
        const double left = rate > 0 ? static_cast<double>(t - d) / rate : 0.0;
        char buf[400];
        std::snprintf(buf, sizeof buf, "\r%llu/%llu %s, %.1f s elapsed, ~%.0f s left   %s",
                      static_cast<unsigned long long>(d), static_cast<unsigned long long>(t), what.c_str(), s, left,
                      final ? "\n" : "");
        try {
            py::object err = py::module_::import("sys").attr("stderr");
            if (err.is_none()) return;
            err.attr("write")(std::string(buf));
            err.attr("flush")();
        } catch (py::error_already_set&) {
        }
    }
};

/// Runs work() on a helper thread with the GIL released; Ctrl-C (any Python
/// exception raised by a signal handler) cancels it through `mon` and is
/// re-raised. Called with the GIL held.
template <class Result>
Result run_interruptible(std::function<Result()> work, Monitor& mon, bool show_progress) {
    std::optional<py::error_already_set> interrupted;
    std::future<Result> fut;
    {
        py::gil_scoped_release nogil;
        fut = std::async(std::launch::async, std::move(work));
        auto last_print = std::chrono::steady_clock::now();
        while (fut.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
            py::gil_scoped_acquire gil;
            if (!interrupted && PyErr_CheckSignals() != 0) {
                interrupted.emplace(); // fetches (and clears) the pending exception
                mon.cancel = true;
            }
            const auto now = std::chrono::steady_clock::now();
            if (show_progress && !interrupted && now - last_print >= std::chrono::milliseconds(500)) {
                last_print = now;
                mon.print(false);
            }
        }
    }
    if (show_progress && interrupted) {
        try {
            py::module_::import("sys").attr("stderr").attr("write")("\n");
        } catch (py::error_already_set&) {
        }
    }
    try {
        Result r = fut.get();
        if (interrupted) throw *interrupted; // finished before it could stop: still honour Ctrl-C
        if (show_progress) mon.print(true);
        return r;
    } catch (const RunCancelled&) {
        if (interrupted) throw *interrupted;
        throw;
    }
}

struct RunArgs {
    std::uint64_t seed = 1;
    unsigned threads = 0;
    double level = 0.95;
    bool progress = false;
};

void apply(RunControl& c, const RunArgs& a) {
    c.seed = a.seed;
    c.threads = a.threads;
    c.progress_interval = 0.0; // check the cancel flag after every merged block
}

template <class Request, class Result>
Result run_request(Request& req, Result (*compute)(const Request&), const RunArgs& a, const char* what) {
    apply(req.control, a);
    validate(req); // bad input fails here, before any thread starts
    Monitor mon;
    req.control.progress = mon.callback(what);
    req.control.cancel = &mon.cancel; // stops the workers within one sample

    Result r = run_interruptible<Result>([&req, compute] { return compute(req); }, mon, a.progress);
    r.request.control.progress = nullptr; // it points to `mon`, about to go
    r.request.control.cancel = nullptr;
    return r;
}

double none_to_nan(const py::object& x) { return x.is_none() ? kNaN : x.cast<double>(); }

// ---- renderings shared by every result class -------------------------------------

template <class R, class Cls>
void add_renderings(Cls& cls) {
    cls.def(
           "to_json", [](const R& r, int indent) { return to_json(r, indent); }, py::arg("indent") = 2,
           "The CLI's --format json output (indent -1: one line).")
        .def(
            "to_dict", [](const R& r) { return json_loads(to_json(r, -1)); },
            "json.loads(self.to_json()): exactly the object the CLI prints with --format json.")
        .def("to_table", [](const R& r) { return to_table(r); }, "The CLI's --format table output.")
        .def("to_csv", [](const R& r) { return to_csv(r); }, "The CLI's --format csv output.")
        .def_readonly("warnings", &R::warnings, "Notes on the result (list of str), as in the CLI output.");
}

template <class R, class Cls>
void add_request_params(Cls& cls) {
    cls.def_property_readonly(
        "params", [](const R& r) { return r.request.params; }, "The model parameters of the run (Params).");
}

template <class R, class Cls>
void add_totals(Cls& cls) {
    cls.def_property_readonly(
           "capped", [](const R& r) { return r.totals.capped; },
           "samples dropped by the runaway guard (max_steps)")
        .def_property_readonly(
            "work", [](const R& r) { return r.totals.work; }, "steps (inclusion) or events (pdmp), all samples")
        .def_property_readonly(
            "seconds", [](const R& r) { return r.totals.seconds; }, "wall time of the run [s]")
        .def_property_readonly(
            "threads", [](const R& r) { return r.totals.threads; }, "worker threads used");
}

/// D, M0, E[t1] of the long excursions behind a result.
template <class Cls, class Get>
void add_long_excursion(Cls& cls, Get get) {
    using R = typename Cls::type;
    cls.def_property_readonly(
           "diffusivity", [get](const R& r) { return get(r).diffusivity; }, "D [m^2/s] (Estimate)")
        .def_property_readonly(
            "mobility", [get](const R& r) { return get(r).mobility; }, "M0, the mean velocity [m/s] (Estimate)")
        .def_property_readonly(
            "mean_duration", [get](const R& r) { return get(r).mean_duration; },
            "E[t1], mean duration of a long excursion [s] (Estimate)")
        .def_property_readonly(
            "completed", [get](const R& r) { return get(r).excursions; }, "completed long excursions");
}

EstimateSeries series(const std::vector<Estimate>& v, double level) { return EstimateSeries{v, level}; }

std::string g4(double x) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.4g", x);
    return buf;
}

std::string estimate_short(const Estimate& e) { return g4(e.value) + " +- " + g4(e.std_error); }

py::array_t<double> centers(const std::vector<double>& edges) {
    const std::size_t n = edges.empty() ? 0 : edges.size() - 1;
    py::array_t<double> a(static_cast<py::ssize_t>(n));
    for (std::size_t k = 0; k < n; ++k) a.mutable_data()[k] = 0.5 * (edges[k] + edges[k + 1]);
    return a;
}

py::array_t<double> widths(const std::vector<double>& edges) {
    const std::size_t n = edges.empty() ? 0 : edges.size() - 1;
    py::array_t<double> a(static_cast<py::ssize_t>(n));
    for (std::size_t k = 0; k < n; ++k) a.mutable_data()[k] = edges[k + 1] - edges[k];
    return a;
}

} // namespace

void bind_results(py::module_& m) {
    py::class_<RunArgs>(m, "_RunArgs")
        .def(py::init([](std::uint64_t seed, unsigned threads, double level, bool progress) {
                 if (std::isnan(level)) throw InvalidParameter("level", "level must be a number, got NaN");
                 return RunArgs{seed, threads, level, progress};
             }),
             py::arg("seed"), py::arg("threads"), py::arg("level"), py::arg("progress"));

    // ---- histograms and paths ----------------------------------------------------------------
    py::class_<VelocityHistogram>(m, "Histogram",
                                  "A velocity density histogram with error bars. `density` is the density of the "
                                  "continuous part of the law of V [s/m] on the bins [edges[k], edges[k+1]) [m/s]; "
                                  "the atom at V = 0 is `stuck` (a probability), so that "
                                  "sum(density.value * widths) + stuck + below + above = 1.")
        .def_property_readonly(
            "edges", [](const VelocityHistogram& h) { return to_array(h.edges); }, "bin edges [m/s], shape (bins + 1,)")
        .def_property_readonly(
            "centers", [](const VelocityHistogram& h) { return centers(h.edges); }, "bin centres [m/s], shape (bins,)")
        .def_property_readonly(
            "widths", [](const VelocityHistogram& h) { return widths(h.edges); }, "bin widths [m/s], shape (bins,)")
        .def_property_readonly(
            "density", [](const VelocityHistogram& h) { return series(h.density, h.stuck.level); },
            "density [s/m] per bin (EstimateSeries, shape (bins,))")
        .def_readonly("stuck", &VelocityHistogram::stuck, "P(V = 0), the object sticks (Estimate)")
        .def_readonly("below", &VelocityHistogram::below, "P(V < edges[0], V != 0) (Estimate)")
        .def_readonly("above", &VelocityHistogram::above, "P(V >= edges[-1], V != 0) (Estimate)")
        .def("__repr__", [](const VelocityHistogram& h) {
            return "Histogram(bins=" + std::to_string(h.density.size()) + ", range=(" + g4(h.edges.front()) + ", " +
                   g4(h.edges.back()) + "), stuck=" + g4(h.stuck.value) + ")";
        });

    py::class_<SamplePath>(m, "Path",
                           "One recorded path, columns of equal length: t [s], x (the paper's noise X [s^-1/2], 0 "
                           "for white noise), mode (-1/0/+1: negative-dynamic/static/positive-dynamic), v [m/s], "
                           "u (displacement) [m].")
        .def_property_readonly("t", [](const SamplePath& p) { return to_array(p.t); })
        .def_property_readonly("x", [](const SamplePath& p) { return to_array(p.x); })
        .def_property_readonly("mode", [](const SamplePath& p) { return to_array(p.mode); })
        .def_property_readonly("v", [](const SamplePath& p) { return to_array(p.v); })
        .def_property_readonly("u", [](const SamplePath& p) { return to_array(p.u); })
        .def("__len__", [](const SamplePath& p) { return p.t.size(); })
        .def(
            "to_dict",
            [](const SamplePath& p) {
                py::dict d;
                d["t"] = to_array(p.t);
                d["x"] = to_array(p.x);
                d["mode"] = to_array(p.mode);
                d["v"] = to_array(p.v);
                d["u"] = to_array(p.u);
                return d;
            },
            "{'t', 'x', 'mode', 'v', 'u'} as NumPy arrays")
        .def("__repr__", [](const SamplePath& p) {
            return "Path(points=" + std::to_string(p.t.size()) +
                   (p.t.empty() ? std::string() : ", t=[" + g4(p.t.front()) + ", " + g4(p.t.back()) + "]") + ")";
        });

    // ---- diffusivity ------------------------------------------------------------------------
    {
        py::class_<DiffusivityResult> c(m, "DiffusivityResult",
                                        "D, M0 and E[t1] from long excursions (stickslip.diffusivity). "
                                        "to_dict() is the CLI's JSON.");
        add_long_excursion(c, [](const DiffusivityResult& r) -> const LongExcursionEstimates& { return r.estimates; });
        add_totals<DiffusivityResult>(c);
        add_request_params<DiffusivityResult>(c);
        add_renderings<DiffusivityResult>(c);
        c.def_property_readonly("engine", [](const DiffusivityResult& r) { return to_string(r.request.engine.engine); })
            .def_property_readonly("estimator",
                                   [](const DiffusivityResult& r) { return to_string(r.request.estimator); })
            .def_property_readonly(
                "stop_rule", [](const DiffusivityResult& r) { return r.resolved.stop_rule; },
                "'bridge', 'stuck', 'velocity-levels' (white noise) or 'exact' (pdmp)")
            .def_property_readonly("excursions", [](const DiffusivityResult& r) { return r.request.excursions; },
                                   "excursions requested")
            .def_property_readonly("seed", [](const DiffusivityResult& r) { return r.request.control.seed; })
            .def_property_readonly("level", [](const DiffusivityResult& r) { return r.request.level; })
            .def_property_readonly(
                "precision",
                [](const DiffusivityResult& r) -> py::object {
                    if (r.request.rel_precision <= 0) return py::none();
                    py::dict d;
                    d["target"] = r.precision.target;
                    d["relative_half_width"] = r.precision.relative_half_width;
                    d["reached"] = r.precision.reached;
                    d["batches"] = r.precision.batches;
                    return d;
                },
                "precision on demand (rel_precision > 0): {'target', 'relative_half_width', 'reached', "
                "'batches'}; None otherwise")
            .def("__repr__", [](const DiffusivityResult& r) {
                return "DiffusivityResult(diffusivity=" + estimate_short(r.estimates.diffusivity) +
                       " m^2/s, mobility=" + estimate_short(r.estimates.mobility) +
                       " m/s, mean_duration=" + estimate_short(r.estimates.mean_duration) +
                       " s, completed=" + std::to_string(r.estimates.excursions) + ", engine='" +
                       to_string(r.request.engine.engine) + "')";
            });
        m.def(
            "_diffusivity",
            [](const ModelParams& p, const EngineSettings& e, std::uint64_t excursions, const std::string& estimator,
               bool allow_capped, double rel_precision, std::uint64_t max_excursions, const RunArgs& a) {
                DiffusivityRequest req;
                req.params = p;
                req.engine = e;
                req.excursions = excursions;
                req.estimator = parse_estimator(estimator);
                req.allow_capped = allow_capped;
                req.rel_precision = rel_precision;
                req.max_excursions = max_excursions;
                req.level = a.level;
                return run_request(req, &compute_diffusivity, a, "excursions");
            },
            py::arg("params"), py::arg("engine"), py::arg("excursions"), py::arg("estimator"),
            py::arg("allow_capped"), py::arg("rel_precision"), py::arg("max_excursions"), py::arg("run"));
    }

    // ---- bruteforce ---------------------------------------------------------------------------
    {
        py::class_<BruteForceResult> c(m, "BruteForceResult",
                                       "Brute-force D_t = var U(t)/t and U(t)/t from independent trajectories "
                                       "(stickslip.bruteforce). to_dict() is the CLI's JSON.");
        add_totals<BruteForceResult>(c);
        add_request_params<BruteForceResult>(c);
        add_renderings<BruteForceResult>(c);
        c.def_property_readonly(
             "diffusivity", [](const BruteForceResult& r) { return r.estimates.diffusivity; },
             "D_t = var U(t)/t [m^2/s] (Estimate; biased against D by O(1/t))")
            .def_property_readonly(
                "mobility", [](const BruteForceResult& r) { return r.estimates.mobility; },
                "mean U(t)/t [m/s] (Estimate)")
            .def_property_readonly("trajectories", [](const BruteForceResult& r) { return r.estimates.trajectories; })
            .def_property_readonly(
                "time", [](const BruteForceResult& r) { return r.estimates.horizon; }, "horizon t [s]")
            .def_property_readonly(
                "x0", [](const BruteForceResult& r) { return r.start_noise; }, "initial noise used [s^-1/2]")
            .def_property_readonly("v0", [](const BruteForceResult& r) { return r.request.v0; })
            .def_property_readonly("engine", [](const BruteForceResult& r) { return to_string(r.request.engine.engine); })
            .def("__repr__", [](const BruteForceResult& r) {
                return "BruteForceResult(diffusivity=" + estimate_short(r.estimates.diffusivity) +
                       " m^2/s, mobility=" + estimate_short(r.estimates.mobility) +
                       " m/s, time=" + g4(r.estimates.horizon) +
                       " s, trajectories=" + std::to_string(r.estimates.trajectories) + ")";
            });
        m.def(
            "_bruteforce",
            [](const ModelParams& p, const EngineSettings& e, double time, std::uint64_t trajectories,
               const py::object& x0, double v0, const RunArgs& a) {
                BruteForceRequest req;
                req.params = p;
                req.engine = e;
                req.horizon = time;
                req.trajectories = trajectories;
                req.x0 = none_to_nan(x0);
                req.v0 = v0;
                req.level = a.level;
                return run_request(req, &compute_bruteforce, a, "trajectories");
            },
            py::arg("params"), py::arg("engine"), py::arg("time"), py::arg("trajectories"), py::arg("x0"),
            py::arg("v0"), py::arg("run"));
    }

    // ---- stationary density -------------------------------------------------------------------
    {
        using R = StationaryDensityResult;
        py::class_<R> c(m, "DensityResult",
                        "Stationary velocity density with error bars (stickslip.density): a histogram of the "
                        "continuous part of the law of V plus the atom P(V = 0), and D, M0, E[t1] of the same "
                        "excursions. to_dict() is the CLI's JSON.");
        add_long_excursion(c, [](const R& r) -> const LongExcursionEstimates& { return r.estimates; });
        add_totals<R>(c);
        add_request_params<R>(c);
        add_renderings<R>(c);
        c.def_property_readonly(
             "histogram", [](const R& r) { return r.histogram; }, "the Histogram (edges, density, stuck, ...)")
            .def_property_readonly(
                "edges", [](const R& r) { return to_array(r.histogram.edges); }, "bin edges [m/s], shape (bins + 1,)")
            .def_property_readonly(
                "centers", [](const R& r) { return centers(r.histogram.edges); }, "bin centres [m/s], shape (bins,)")
            .def_property_readonly(
                "density", [](const R& r) { return series(r.histogram.density, r.request.level); },
                "density [s/m] per bin (EstimateSeries, shape (bins,)), V = 0 excluded")
            .def_property_readonly(
                "stuck", [](const R& r) { return r.histogram.stuck; }, "P(V = 0) (Estimate)")
            .def_property_readonly(
                "below", [](const R& r) { return r.histogram.below; }, "P(V < edges[0], V != 0) (Estimate)")
            .def_property_readonly(
                "above", [](const R& r) { return r.histogram.above; }, "P(V >= edges[-1], V != 0) (Estimate)")
            .def_readonly("mean", &R::mean, "stationary E[V] = M0 [m/s] (Estimate)")
            .def_readonly("variance", &R::variance, "stationary Var(V) [m^2/s^2] (Estimate)")
            .def("__repr__", [](const R& r) {
                return "DensityResult(bins=" + std::to_string(r.histogram.density.size()) + ", range=(" +
                       g4(r.histogram.edges.front()) + ", " + g4(r.histogram.edges.back()) +
                       ") m/s, stuck=" + estimate_short(r.histogram.stuck) + ", mean=" + estimate_short(r.mean) +
                       " m/s, completed=" + std::to_string(r.estimates.excursions) + ")";
            });
        m.def(
            "_density",
            [](const ModelParams& p, const EngineSettings& e, std::uint64_t excursions, int bins, double lo,
               double hi, double sample_dt, bool allow_capped, const RunArgs& a) {
                StationaryDensityRequest req;
                req.params = p;
                req.engine = e;
                req.excursions = excursions;
                req.bins.count = bins;
                req.bins.lo = lo;
                req.bins.hi = hi;
                req.sample_dt = sample_dt;
                req.allow_capped = allow_capped;
                req.level = a.level;
                return run_request(req, &compute_stationary_density, a, "excursions");
            },
            py::arg("params"), py::arg("engine"), py::arg("excursions"), py::arg("bins"), py::arg("lo"),
            py::arg("hi"), py::arg("sample_dt"), py::arg("allow_capped"), py::arg("run"));
    }

    // ---- correlation -----------------------------------------------------------------------------
    {
        using R = CorrelationResult;
        py::class_<R> c(m, "CorrelationResult",
                        "Stationary autocorrelation <V(0)V(r)>, covariance h(r) and h(r)/h(0) against the lag r "
                        "(stickslip.correlation), and D, M0, E[t1] of the same excursions. to_dict() is the "
                        "CLI's JSON.");
        add_long_excursion(c, [](const R& r) -> const LongExcursionEstimates& { return r.estimates; });
        add_totals<R>(c);
        add_request_params<R>(c);
        add_renderings<R>(c);
        c.def_property_readonly(
             "lag", [](const R& r) { return to_array(r.lag); }, "lags r [s], shape (lags + 1,)")
            .def_property_readonly(
                "autocorrelation", [](const R& r) { return series(r.autocorrelation, r.request.level); },
                "<V(0)V(r)> [m^2/s^2] (EstimateSeries, shape (lags + 1,))")
            .def_property_readonly(
                "covariance", [](const R& r) { return series(r.covariance, r.request.level); },
                "h(r) = <V(0)V(r)> - M0^2 [m^2/s^2] (EstimateSeries)")
            .def_property_readonly(
                "normalised", [](const R& r) { return series(r.normalised, r.request.level); },
                "h(r)/h(0) (EstimateSeries)")
            .def_readonly("mean", &R::mean, "M0 [m/s] (Estimate)")
            .def("__repr__", [](const R& r) {
                return "CorrelationResult(lags=" + std::to_string(r.lag.size()) + ", max_lag=" +
                       g4(r.lag.empty() ? 0.0 : r.lag.back()) + " s, h(0)=" +
                       (r.covariance.empty() ? std::string("-") : estimate_short(r.covariance.front())) +
                       " m^2/s^2, completed=" + std::to_string(r.estimates.excursions) + ")";
            });
        m.def(
            "_correlation",
            [](const ModelParams& p, const EngineSettings& e, std::uint64_t excursions, double max_lag, int lags,
               double sample_dt, bool allow_capped, const RunArgs& a) {
                CorrelationRequest req;
                req.params = p;
                req.engine = e;
                req.excursions = excursions;
                req.max_lag = max_lag;
                req.lags = lags;
                req.sample_dt = sample_dt;
                req.allow_capped = allow_capped;
                req.level = a.level;
                return run_request(req, &compute_correlation, a, "excursions");
            },
            py::arg("params"), py::arg("engine"), py::arg("excursions"), py::arg("max_lag"), py::arg("lags"),
            py::arg("sample_dt"), py::arg("allow_capped"), py::arg("run"));
    }

    // ---- moments (transient) -----------------------------------------------------------------
    {
        using R = TransientResult;
        py::class_<R> c(m, "MomentsResult",
                        "Transient statistics from V(0) = v0 (stickslip.moments): E[V(t)|v0], E[V(t)^2|v0] and "
                        "P(V(t) = 0) at the times `time`, and with density=True one Histogram per time. "
                        "to_dict() is the CLI's JSON.");
        add_totals<R>(c);
        add_request_params<R>(c);
        add_renderings<R>(c);
        c.def_property_readonly(
             "time", [](const R& r) { return to_array(r.time); },
             "times t [s] actually used (sorted; inclusion: whole steps), shape (n,)")
            .def_property_readonly(
                "first_moment", [](const R& r) { return series(r.first_moment, r.request.level); },
                "E[V(t)|v0] [m/s] (EstimateSeries, shape (n,))")
            .def_property_readonly(
                "second_moment", [](const R& r) { return series(r.second_moment, r.request.level); },
                "E[V(t)^2|v0] [m^2/s^2] (EstimateSeries)")
            .def_property_readonly(
                "stuck", [](const R& r) { return series(r.stuck, r.request.level); }, "P(V(t) = 0) (EstimateSeries)")
            .def_readonly("density", &R::density,
                          "list of Histogram, one per time (empty unless density=True)")
            .def_property_readonly("v0", [](const R& r) { return r.request.v0; }, "initial velocity [m/s]")
            .def_property_readonly(
                "trajectories", [](const R& r) { return r.request.trajectories; }, "trajectories requested")
            .def("__repr__", [](const R& r) {
                return "MomentsResult(times=" + std::to_string(r.time.size()) + ", v0=" + g4(r.request.v0) +
                       " m/s, trajectories=" + std::to_string(r.request.trajectories) +
                       ", density=" + (r.density.empty() ? "False" : "True") + ")";
            });
        m.def(
            "_moments",
            [](const ModelParams& p, const EngineSettings& e, double v0, const py::object& x0,
               const std::vector<double>& times, std::uint64_t trajectories, bool density, int bins, double lo,
               double hi, const RunArgs& a) {
                TransientRequest req;
                req.params = p;
                req.engine = e;
                req.v0 = v0;
                req.x0 = none_to_nan(x0);
                req.times = times;
                req.trajectories = trajectories;
                req.with_density = density;
                req.bins.count = bins;
                req.bins.lo = lo;
                req.bins.hi = hi;
                req.level = a.level;
                return run_request(req, &compute_transient, a, "trajectories");
            },
            py::arg("params"), py::arg("engine"), py::arg("v0"), py::arg("x0"), py::arg("times"),
            py::arg("trajectories"), py::arg("density"), py::arg("bins"), py::arg("lo"), py::arg("hi"),
            py::arg("run"));
    }

    // ---- trajectory ----------------------------------------------------------------------------
    {
        using R = TrajectoryResult;
        py::class_<R> c(m, "TrajectoryResult",
                        "Sample paths (stickslip.trajectory): `paths` is a list of Path (t, x, mode, v, u arrays). "
                        "In excursion mode (paths=0) there is one path, also `path`, with its displacement, "
                        "duration and whether it is complete. to_dict() is the CLI's JSON.");
        add_request_params<R>(c);
        add_renderings<R>(c);
        c.def_readonly("paths", &R::paths, "list of Path")
            .def_property_readonly(
                "path",
                [](const R& r) {
                    if (r.paths.empty()) throw py::index_error("no path recorded");
                    return r.paths.front();
                },
                "the first (in excursion mode: the only) Path")
            .def_property_readonly(
                "displacement", [](const R& r) { return r.excursion.displacement; },
                "excursion mode: U of the excursion [m]")
            .def_property_readonly(
                "duration", [](const R& r) { return r.excursion.duration; }, "excursion mode: its duration [s]")
            .def_property_readonly(
                "complete", [](const R& r) { return !r.excursion.capped; },
                "excursion mode: False if it hit the runaway guard (max_steps)")
            .def_property_readonly(
                "work", [](const R& r) { return r.excursion.work; }, "excursion mode: steps or events used")
            .def("__repr__", [](const R& r) {
                std::size_t points = 0;
                for (const auto& p : r.paths) points += p.t.size();
                return "TrajectoryResult(paths=" + std::to_string(r.paths.size()) +
                       ", points=" + std::to_string(points) +
                       (r.request.paths == 0 ? ", duration=" + g4(r.excursion.duration) +
                                                   " s, displacement=" + g4(r.excursion.displacement) + " m"
                                             : std::string()) +
                       ")";
            });
        m.def(
            "_trajectory",
            [](const ModelParams& p, const EngineSettings& e, std::uint64_t index, std::uint64_t paths, double time,
               const py::object& x0, double v0, double every, std::uint64_t max_points, const RunArgs& a) {
                TrajectoryRequest req;
                req.params = p;
                req.engine = e;
                req.index = index;
                req.paths = paths;
                req.horizon = time;
                req.x0 = none_to_nan(x0);
                req.v0 = v0;
                req.every = every;
                req.max_points = max_points;
                return run_request(req, &compute_trajectory, a, "paths");
            },
            py::arg("params"), py::arg("engine"), py::arg("index"), py::arg("paths"), py::arg("time"),
            py::arg("x0"), py::arg("v0"), py::arg("every"), py::arg("max_points"), py::arg("run"));
    }

    // ---- sweep ---------------------------------------------------------------------------------
    {
        using R = SweepResult;
        py::class_<SweepExponent>(m, "SweepExponent",
                                  "Fitted exponent alpha of D ~ noise^alpha at one tau (weighted least squares in "
                                  "log-log), with chi^2/dof of the fit (>> 1: no single power law).")
            .def_readonly("tau", &SweepExponent::tau, "[s]")
            .def_readonly("exponent", &SweepExponent::exponent, "alpha (Estimate)")
            .def_readonly("chi2_per_dof", &SweepExponent::chi2_per_dof)
            .def_readonly("points", &SweepExponent::points)
            .def("__repr__", [](const SweepExponent& e) {
                return "SweepExponent(tau=" + g4(e.tau) + ", exponent=" + estimate_short(e.exponent) +
                       ", chi2_per_dof=" + g4(e.chi2_per_dof) + ", points=" + std::to_string(e.points) + ")";
            });
        py::class_<R> c(m, "SweepResult",
                        "D, M0 and E[t1] over a grid of noise and tau (stickslip.sweep). Points are tau-major "
                        "(for each tau in `taus`, the noises in `noises`, both sorted and deduplicated), so "
                        "r.diffusivity.value.reshape(r.shape) has shape (len(taus), len(noises)). "
                        "to_dict() is the CLI's JSON.");
        add_renderings<R>(c);
        auto column = [](const R& r, auto get) {
            std::vector<Estimate> v;
            v.reserve(r.points.size());
            for (const auto& p : r.points) v.push_back(get(p));
            return series(v, r.request.level);
        };
        c.def_property_readonly(
             "params", [](const R& r) { return r.request.params; },
             "friction, relaxation and bias of the sweep (Params; its noise and tau are placeholders)")
            .def_property_readonly(
                "noises", [](const R& r) { return to_array(r.request.noises); }, "the noise grid [m^2 s^-3], sorted")
            .def_property_readonly(
                "taus", [](const R& r) { return to_array(r.request.taus); }, "the tau grid [s], sorted")
            .def_property_readonly(
                "shape", [](const R& r) { return py::make_tuple(r.request.taus.size(), r.request.noises.size()); },
                "(len(taus), len(noises))")
            .def_property_readonly(
                "noise",
                [](const R& r) {
                    std::vector<double> v;
                    for (const auto& p : r.points) v.push_back(p.noise);
                    return to_array(v);
                },
                "noise of every point [m^2 s^-3], shape (points,)")
            .def_property_readonly(
                "tau",
                [](const R& r) {
                    std::vector<double> v;
                    for (const auto& p : r.points) v.push_back(p.tau);
                    return to_array(v);
                },
                "tau of every point [s], shape (points,)")
            .def_property_readonly(
                "diffusivity",
                [column](const R& r) { return column(r, [](const SweepPoint& p) { return p.estimates.diffusivity; }); },
                "D [m^2/s] per point (EstimateSeries)")
            .def_property_readonly(
                "mobility",
                [column](const R& r) { return column(r, [](const SweepPoint& p) { return p.estimates.mobility; }); },
                "M0 [m/s] per point (EstimateSeries)")
            .def_property_readonly(
                "mean_duration",
                [column](const R& r) { return column(r, [](const SweepPoint& p) { return p.estimates.mean_duration; }); },
                "E[t1] [s] per point (EstimateSeries)")
            .def_property_readonly(
                "slope", [column](const R& r) { return column(r, [](const SweepPoint& p) { return p.slope; }); },
                "local d log D / d log noise per point (EstimateSeries; NaN with one noise value)")
            .def_property_readonly(
                "stop_rule",
                [](const R& r) {
                    std::vector<std::string> v;
                    for (const auto& p : r.points) v.push_back(p.stop_rule);
                    return v;
                },
                "stop rule used at every point (list of str)")
            .def_readonly("exponents", &R::exponents, "one SweepExponent per tau (with >= 2 noises)")
            .def_readonly("seconds", &R::seconds, "wall time [s]")
            .def("__repr__", [](const R& r) {
                return "SweepResult(taus=" + std::to_string(r.request.taus.size()) +
                       ", noises=" + std::to_string(r.request.noises.size()) +
                       ", excursions=" + std::to_string(r.request.excursions) + " per point)";
            });
        m.def(
            "_sweep",
            [](const ModelParams& p, const EngineSettings& e, const std::vector<double>& noises,
               const std::vector<double>& taus, std::uint64_t excursions, const std::string& estimator,
               bool allow_capped, const RunArgs& a) {
                SweepRequest req;
                req.params = p;
                req.params.noise = 1.0; // placeholders, as in the CLI: every point sets its own
                req.params.tau = 1.0;
                req.engine = e;
                req.noises = noises;
                req.taus = taus;
                req.excursions = excursions;
                req.estimator = parse_estimator(estimator);
                req.allow_capped = allow_capped;
                req.level = a.level;
                apply(req.control, a);
                validate(req);
                Monitor mon;
                req.point_progress = [&mon](std::size_t k, std::size_t n, double noise, double tau) {
                    char what[160];
                    std::snprintf(what, sizeof what, "excursions (point %zu/%zu: noise %g, tau %g)", k + 1, n,
                                  noise, tau);
                    return mon.callback(what);
                };
                req.control.cancel = &mon.cancel; // every point's run stops within one sample
                SweepResult r =
                    run_interruptible<SweepResult>([&req] { return compute_sweep(req); }, mon, a.progress);
                r.request.point_progress = nullptr; // it points to `mon`, about to go
                r.request.control.cancel = nullptr;
                return r;
            },
            py::arg("params"), py::arg("engine"), py::arg("noises"), py::arg("taus"), py::arg("excursions"),
            py::arg("estimator"), py::arg("allow_capped"), py::arg("run"));
    }
}

} // namespace stickslip::python
