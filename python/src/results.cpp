// SPDX-License-Identifier: BSD-3-Clause
// The result classes of the simulations (what stickslip.run returns for each
// request, requests.cpp): attributes as NumPy arrays and Estimates, and the
// CLI's renderings (to_dict() is the CLI's JSON).
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "bindings.hpp"
#include "stickslip/bruteforce.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/number_text.hpp"
#include "stickslip/observables.hpp"
#include "stickslip/report.hpp"
#include "stickslip/spectrum.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::python {

namespace {

template <class R, class Cls>
void add_request_params(Cls& cls) {
    cls.def_property_readonly(
        "params", [](const R& r) { return r.request.params; }, "The model parameters of the run (Params).");
}

/// A sampled result's run totals: the declared ones (RunTotals::fields) and
/// the thread count and interruption, which a solved result answers too.
template <class R, class Cls>
void add_totals(Cls& cls) {
    add_declared_fields(cls, [](const R& r) -> const RunTotals& { return r.monte_carlo().totals; });
    cls.def_property_readonly(
           "threads", [](const R& r) { return r.monte_carlo().totals.threads; }, "worker threads used")
        .def_property_readonly(
            "interrupted",
            [](const R& r) {
                if constexpr (requires { r.solution; })
                    if (r.solution) return r.solution->interrupted; // engine='kolmogorov': its rounds so far
                return r.monte_carlo().totals.interrupted;
            },
            "True when the run was stopped early (Ctrl-C): the result is of the blocks completed, in index order "
            "(engine='kolmogorov': of the rounds of grids finished)");
}

EstimateSeries series(const std::vector<Estimate>& v, double level) { return EstimateSeries{v, level, {}}; }

std::string g4(double x) { return number_text::general(x, 4); }

std::string estimate_short(const Estimate& e) { return g4(e.value) + " +- " + g4(e.error); }

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
    // Seen from Python as a dict of its JSON block (DiffusivityResult.control_variate).
    note_declared<ControlVariateReport>("", "control_variate");
    note_declared<PrecisionOutcome>("", "merged:precision"); // a dict of its JSON block, as above
    // Flattened into the sampled results (add_totals); capped merged into these reports.
    note_declared<RunTotals>("_Totals", "merged:diffusivity_report,stationary_density_report");
    note_declared<NondimensionalValues>("", "merged:nondimensional"); // in every report's nondimensional block
    note_declared<RunWork>("", "work"); // every report's work block, a dict in Python's to_dict()
    note_declared<SweepPoint>("", "merged:sweep_point"); // SweepResult's grid columns, by hand
    note_declared<KolmogorovGridSpan>("", "kolmogorov_grid"); // in a solved report's engine_details, a dict
    note_declared<DiscretisationCheck>("", "difference_check"); // the same
    note_declared<BruteForceEstimates>("", "merged:finite_time_diffusivity_report"); // flattened, as above
    // Merged into the top level of these reports, and flattened into their results (add_declared_fields).
    note_declared<LongExcursionEstimates>(
        "_LongExcursions", "merged:diffusivity_report,stationary_density_report,autocorrelation_report,sweep_point");
    // ---- histograms and paths ----------------------------------------------------------------
    {
        py::class_<VelocityHistogram> histogram(
            m, "Histogram",
            "A velocity density histogram with error bars. `bins` is the density of the continuous part of the law "
            "of V [s/m] on the bins [edges[k], edges[k+1]) [m/s]; the atom at V = 0 is `stuck_probability`, so that "
            "sum(bins.value * widths) + stuck_probability + below + above = 1.");
        bind_fields<VelocityHistogram>(histogram, "Histogram", "histogram");
        histogram
            .def_property_readonly(
                "centers", [](const VelocityHistogram& h) { return centers(h.edges); },
                "bin centres [m/s], shape (bins,)")
            .def_property_readonly(
                "widths", [](const VelocityHistogram& h) { return widths(h.edges); }, "bin widths [m/s], shape (bins,)")
            .def_property_readonly(
                "density", [](const VelocityHistogram& h) { return estimate_series(h.density); },
                "the same as `bins` (its older name): the density [s/m] per bin (EstimateSeries, shape (bins,))")
            .def("__repr__", [](const VelocityHistogram& h) {
                return "Histogram(bins=" + std::to_string(h.density.size()) + ", range=(" + g4(h.edges.front()) +
                       ", " + g4(h.edges.back()) + "), stuck_probability=" + g4(h.stuck.value) + ")";
            });
    }

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
        add_declared_fields(c, [](const DiffusivityResult& r) -> const LongExcursionEstimates& { return r.estimates; });
        add_totals<DiffusivityResult>(c);
        add_request_params<DiffusivityResult>(c);
        add_renderings<DiffusivityResult>(c);
        // A solved result (engine='kolmogorov') has D, M0 and P(V = 0) as
        // GridEstimates (value, error) and no samples.
        c.def_property_readonly(
                "stuck_probability",
                [](const DiffusivityResult& r) -> py::object {
                    if (r.solution) return py::cast(r.solution->stuck_probability);
                    return py::none();
                },
                "P(V = 0) (Estimate of kind 'solved') with engine='kolmogorov'; None for a sampled result")
            .def_property_readonly(
                "method", [](const DiffusivityResult& r) -> std::string {
                    return r.sampled() ? std::string("monte carlo") : r.grid().solver;
                },
                "'monte carlo', or the grid solver ('kolmogorov') with engine='kolmogorov'");
        c.def_property_readonly("engine", [](const DiffusivityResult& r) { return to_string(r.request.engine.engine); })
            .def_property_readonly("estimator",
                                   [](const DiffusivityResult& r) { return to_string(r.request.estimator); })
            .def_property_readonly(
                "stop_rule", [](const DiffusivityResult& r) { return r.monte_carlo().engine.stop_rule; },
                "'bridge', 'stuck', 'velocity-levels' (white noise) or 'exact' (pdmp)")
            .def_property_readonly("excursions", [](const DiffusivityResult& r) { return r.request.excursions; },
                                   "excursions requested")
            .def_property_readonly("seed", [](const DiffusivityResult& r) { return r.request.control.seed; })
            .def_property_readonly("level", [](const DiffusivityResult& r) { return r.request.level; })
            .def_property_readonly(
                "precision",
                [](const DiffusivityResult& r) -> py::object {
                    if (r.request.rel_precision <= 0) return py::none();
                    return json_loads(to_json(r, -1))["precision"]; // the JSON's layout, defined once
                },
                ("precision on demand (rel_precision > 0), a dict of the JSON's block: " +
                 block_doc<PrecisionOutcome>() + "; None otherwise")
                    .c_str())
            .def_property_readonly(
                "discretisation",
                [](const DiffusivityResult& r) -> py::object {
                    if (!r.discretisation) return py::none();
                    return json_loads(to_json(r, -1))["discretisation"]; // the JSON's layout, defined once
                },
                ("check_dt=True, a dict of the JSON's block: " + block_doc<DiscretisationCheck>() +
                 " (the coarse run at 2 dt); None otherwise")
                    .c_str())
            .def_property_readonly(
                "control_variate",
                [](const DiffusivityResult& r) -> py::object {
                    if (!r.control_variate) return py::none();
                    return json_loads(to_json(r, -1))["control_variate"]; // the JSON's layout, defined once
                },
                ("when the martingale control variate ran (control_variate='auto' and a corrector), a dict of "
                 "the JSON's block: " +
                 block_doc<ControlVariateReport>() +
                 ". diffusivity and mobility are then its estimates and ['plain'] the estimates without it; None "
                 "otherwise")
                    .c_str())
            .def("__repr__", [](const DiffusivityResult& r) {
                if (r.solution)
                    return "DiffusivityResult(diffusivity=" + g4(r.solution->diffusivity.value) + " +- " +
                           g4(r.solution->diffusivity.error) + " m^2/s, mobility=" + g4(r.solution->mobility.value) +
                           " +- " + g4(r.solution->mobility.error) + " m/s, stuck_probability=" +
                           g4(r.solution->stuck_probability.value) + " +- " + g4(r.solution->stuck_probability.error) +
                           ", mean_duration=" + g4(r.solution->mean_duration.value) + " +- " +
                           g4(r.solution->mean_duration.error) + " s, engine='kolmogorov' (discretisation errors))";
                return "DiffusivityResult(diffusivity=" + estimate_short(r.estimates.diffusivity) +
                       " m^2/s, mobility=" + estimate_short(r.estimates.mobility) +
                       " m/s, mean_duration=" + estimate_short(r.estimates.mean_duration) +
                       " s, completed=" + std::to_string(r.estimates.excursions) + ", engine='" +
                       to_string(r.request.engine.engine) + "'" +
                       (r.control_variate ? ", variance_reduction=" + g4(r.control_variate->variance_reduction) : "") +
                       ")";
            });

    }

    // ---- bruteforce ---------------------------------------------------------------------------
    {
        py::class_<BruteForceResult> c(m, "BruteForceResult",
                                       "Brute-force D_t = var U(t)/t and U(t)/t from independent trajectories "
                                       "(stickslip.bruteforce). to_dict() is the CLI's JSON.");
        add_totals<BruteForceResult>(c);
        add_request_params<BruteForceResult>(c);
        add_renderings<BruteForceResult>(c);
        add_declared_fields(c, [](const BruteForceResult& r) -> const BruteForceEstimates& { return r.estimates; });
        c.def_property_readonly(
                "x0", [](const BruteForceResult& r) { return r.start_noise; }, "initial noise used [s^-1/2]")
            .def_property_readonly("v0", [](const BruteForceResult& r) { return r.request.v0; })
            .def_property_readonly("engine", [](const BruteForceResult& r) { return to_string(r.request.engine.engine); })
            .def("__repr__", [](const BruteForceResult& r) {
                return "BruteForceResult(diffusivity=" + estimate_short(r.estimates.diffusivity) +
                       " m^2/s, mobility=" + estimate_short(r.estimates.mobility) +
                       " m/s, time=" + g4(r.estimates.horizon) +
                       " s, trajectories=" + std::to_string(r.estimates.trajectories) + ")";
            });

    }

    // ---- stationary density -------------------------------------------------------------------
    {
        using R = DensityResult;
        py::class_<R> c(m, "DensityResult",
                        "Stationary velocity density with error bars (stickslip.density): a histogram of the "
                        "continuous part of the law of V plus the atom P(V = 0), and D, M0, E[t1] of the same "
                        "excursions. to_dict() is the CLI's JSON.");
        bind_fields<R>(c, "DensityResult", "merged:stationary_density_report");
        add_declared_fields(c, [](const R& r) -> const LongExcursionEstimates& { return r.estimates; });
        add_totals<R>(c);
        add_request_params<R>(c);
        add_renderings<R>(c);
        // A solved result (engine='kolmogorov'): the finest velocity cells as
        // the bins, its density values without error bars, P(V = 0), D and M0
        // as GridEstimates (value, error).
        auto edges_of = [](const R& r) -> const std::vector<double>& {
            return r.solution ? r.solution->levels.back().velocity_faces : r.histogram.edges;
        };
        c.def_property_readonly(
             "histogram", [](const R& r) { return r.histogram; },
             "the Histogram (edges, density, stuck_probability, ...); empty with engine='kolmogorov'")
            .def_property_readonly(
                "edges", [edges_of](const R& r) { return to_array(edges_of(r)); },
                "bin edges [m/s], shape (bins + 1,) (engine='kolmogorov': the grid's velocity cells)")
            .def_property_readonly(
                "centers", [edges_of](const R& r) { return centers(edges_of(r)); }, "bin centres [m/s], shape (bins,)")
            .def_property_readonly(
                "density",
                [](const R& r) -> py::object {
                    if (r.solution) return py::object(to_array(r.solution->levels.back().velocity_density));
                    return py::cast(series(r.histogram.density, r.request.level));
                },
                "density [s/m] per bin (EstimateSeries, shape (bins,)), V = 0 excluded; engine='kolmogorov': "
                "the grid's values (a NumPy array, no error bars)")
            .def_property_readonly(
                "stuck_probability", [](const R& r) { return r.histogram.stuck; },
                "P(V = 0) (Estimate; of kind 'solved' with engine='kolmogorov')")
            .def_property_readonly(
                "below", [](const R& r) { return r.histogram.below; }, "P(V < edges[0], V != 0) (Estimate)")
            .def_property_readonly(
                "above", [](const R& r) { return r.histogram.above; }, "P(V >= edges[-1], V != 0) (Estimate)")
            .def("__repr__", [](const R& r) {
                if (r.solution) {
                    const KolmogorovGridSolution& fine = r.solution->levels.back();
                    return "DensityResult(cells=" + std::to_string(fine.velocity_density.size()) + ", range=(" +
                           g4(fine.velocity_faces.front()) + ", " + g4(fine.velocity_faces.back()) + ") m/s, stuck=" +
                           g4(r.solution->stuck_probability.value) + " +- " + g4(r.solution->stuck_probability.error) +
                           ", mean_duration=" + g4(r.solution->mean_duration.value) + " +- " +
                           g4(r.solution->mean_duration.error) + " s, engine='kolmogorov' (discretisation errors))";
                }
                return "DensityResult(bins=" + std::to_string(r.histogram.density.size()) + ", range=(" +
                       g4(r.histogram.edges.front()) + ", " + g4(r.histogram.edges.back()) +
                       ") m/s, stuck_probability=" + estimate_short(r.histogram.stuck) + ", mean=" + estimate_short(r.mean) +
                       " m/s, completed=" + std::to_string(r.estimates.excursions) + ")";
            });

    }

    // ---- correlation -----------------------------------------------------------------------------
    {
        using R = CorrelationResult;
        py::class_<R> c(m, "CorrelationResult",
                        "Stationary autocorrelation <V(0)V(r)>, covariance h(r) and h(r)/h(0) against the lag r "
                        "(stickslip.correlation), and D, M0, E[t1] of the same excursions. to_dict() is the "
                        "CLI's JSON.");
        bind_fields<R>(c, "CorrelationResult", "merged:autocorrelation_report");
        add_declared_fields(c, [](const R& r) -> const LongExcursionEstimates& { return r.estimates; });
        add_totals<R>(c);
        add_request_params<R>(c);
        add_renderings<R>(c);
        c.def_property_readonly(
             "normalised", [](const R& r) { return estimate_series(r.normalised); },
             "the former name of normalised_covariance (h(r)/h(0), an EstimateSeries)")
            .def("__repr__", [](const R& r) {
                return "CorrelationResult(lags=" + std::to_string(r.lag.size()) + ", max_lag=" +
                       g4(r.lag.empty() ? 0.0 : r.lag.back()) + " s, h(0)=" +
                       (r.covariance.empty() ? std::string("-") : estimate_short(r.covariance.front())) +
                       " m^2/s^2, completed=" + std::to_string(r.estimates.excursions) + ")";
            });

    }

    // ---- moments (transient) -----------------------------------------------------------------
    {
        using R = MomentsResult;
        py::class_<R> c(m, "MomentsResult",
                        "Transient statistics from V(0) = v0 (stickslip.moments): E[V(t)|v0], E[V(t)^2|v0] and "
                        "P(V(t) = 0) at the times `time`, and with density=True one Histogram per time. "
                        "to_dict() is the CLI's JSON.");
        bind_fields<R>(c, "MomentsResult", "merged:transient_report");
        add_totals<R>(c);
        add_request_params<R>(c);
        add_renderings<R>(c);
        c.def_readonly("density", &R::density,
                          "list of Histogram, one per time (empty unless density=True)")
            .def_property_readonly("v0", [](const R& r) { return r.request.v0; }, "initial velocity [m/s]")
            .def_property_readonly(
                "trajectories", [](const R& r) { return r.request.trajectories; }, "trajectories requested")
            .def("__repr__", [](const R& r) {
                return "MomentsResult(times=" + std::to_string(r.time.size()) + ", v0=" + g4(r.request.v0) +
                       " m/s, trajectories=" + std::to_string(r.request.trajectories) +
                       ", density=" + (r.density.empty() ? "False" : "True") + ")";
            });

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
        add_declared_fields(c, [](const R& r) -> const ExcursionRecord& { return r.excursion; });
        note_declared<ExcursionRecord>("TrajectoryResult", "merged:excursion_report");
        c.def_readonly("paths", &R::paths, "list of Path")
            .def_property_readonly(
                "path",
                [](const R& r) {
                    if (r.paths.empty()) throw py::index_error("no path recorded");
                    return r.paths.front();
                },
                "the first (in excursion mode: the only) Path")
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

    }

    // ---- velocity spectrum -----------------------------------------------------------------------
    {
        using R = SpectrumResult;
        py::class_<R> c(m, "SpectrumResult",
                        "Two-sided velocity power spectrum S(w) = int C(t) exp(-i w t) dt (stickslip.spectrum), "
                        "S(0) = D, with D and M0 of the same solve or run: solved by the Kolmogorov engine (each "
                        "value with its estimated discretisation error), exact for white noise without drag, on the "
                        "Fokker-Planck chain for white noise with drag, or "
                        "sampled over long excursions (engine='inclusion' or 'pdmp': standard errors and intervals). "
                        "to_dict() is the CLI's JSON.");
        bind_fields<R>(c, "SpectrumResult", "merged:velocity_spectrum_report");
        add_request_params<R>(c);
        add_renderings<R>(c);
        auto method = [](const R& r) { return r.estimates ? std::string("monte carlo") : r.grid().solver; };
        c.def_property_readonly(
             "diffusivity",
             [](const R& r) {
                 if (r.estimates) return r.estimates->diffusivity;
                 return r.solution ? r.solution->diffusivity : exact_estimate(r.reference->diffusivity);
             },
             "D of the same solve or excursions [m^2/s] (Estimate of kind 'solved', 'exact' or 'sampled'): S(0)")
            .def_property_readonly(
                "mobility",
                [](const R& r) {
                    if (r.estimates) return r.estimates->mobility;
                    return r.solution ? r.solution->mobility : exact_estimate(r.reference->mobility);
                },
                "M0 of the same solve or excursions [m/s] (Estimate of kind 'solved', 'exact' or 'sampled')")
            .def_property_readonly(
                "excursions", [](const R& r) { return r.estimates ? r.estimates->excursions : std::uint64_t{0}; },
                "long excursions completed (0 when solved)")
            .def_property_readonly("method", method,
                                   "'kolmogorov', 'kolmogorov (near-white: ...)', 'closed form (...)', 'fokker-planck (...)' or "
                                   "'monte carlo'")
            .def("__repr__", [method](const R& r) {
                return "SpectrumResult(frequencies=" + std::to_string(r.frequencies.size()) + ", method='" +
                       method(r) + "')";
            });
    }

    // ---- sweep ---------------------------------------------------------------------------------
    {
        using R = SweepResult;
        py::class_<SweepExponent> exponent(m, "SweepExponent",
                                  "Fitted exponent alpha of D ~ noise^alpha at one tau (weighted least squares in "
                                  "log-log), with chi^2/dof of the fit (>> 1: no single power law).");
        bind_fields<SweepExponent>(exponent, "SweepExponent", "sweep_exponent");
        exponent.def("__repr__", [](const SweepExponent& e) {
                return "SweepExponent(" + (std::isnan(e.varied) ? std::string() : "varied=" + g4(e.varied) + ", ") +
                       "tau=" + g4(e.tau) + ", exponent=" + estimate_short(e.exponent) +
                       ", chi2_per_dof=" + g4(e.chi2_per_dof) + ", points=" + std::to_string(e.points) + ")";
            });
        py::class_<SweepWhiteLimit> white_limit(m, "SweepWhiteLimit",
                                    "How D approaches its white-noise value as tau' -> 0 at one noise: 1 - D/D_white "
                                    "fitted as c1 tau'^p (weighted least squares in log-log over the points resolved "
                                    "and within 10%) and as a tau'^(1/2) + b tau' + c tau'^(3/2) (a tests for a "
                                    "tau'^(1/2) law); tau' = tau friction^2/noise.");
        bind_fields<SweepWhiteLimit>(white_limit, "SweepWhiteLimit", "sweep_white_limit");
        white_limit.def("__repr__", [](const SweepWhiteLimit& w) {
                return "SweepWhiteLimit(" + (std::isnan(w.varied) ? std::string() : "varied=" + g4(w.varied) + ", ") +
                       "noise=" + g4(w.noise) + ", exponent=" + estimate_short(w.exponent) +
                       ", coefficient=" + estimate_short(w.coefficient) + ", half_order=" + estimate_short(w.half_order) +
                       ", tau_within_percent=" + g4(w.tau_within_percent) + ", points=" + std::to_string(w.points) + ")";
            });
        py::class_<R> c(m, "SweepResult",
                        "D, M0 and E[t1] over a grid of noise and tau (stickslip.sweep). Points are tau-major "
                        "(for each tau in `taus`, the noises in `noises`, both sorted and deduplicated), and every "
                        "array has shape (len(taus), len(noises)): axis 0 is `taus`, axis 1 `noises`; with vary= "
                        "(a swept constant of the drift expression) a first axis, `vary_values`, comes before them. "
                        "to_dict() is the CLI's JSON.");
        add_renderings<R>(c);
        // (n_tau, n_noise), tau-major as the points are run; the points an
        // interrupted sweep did not reach are NaN.
        // With vary= (a swept drift constant) (n_vary, n_tau, n_noise).
        auto grid_shape = [](const R& r) {
            std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(r.request.taus.size()),
                                           static_cast<py::ssize_t>(r.request.noises.size())};
            if (r.varies()) shape.insert(shape.begin(), static_cast<py::ssize_t>(r.request.vary_values.size()));
            return shape;
        };
        auto grid_size = [grid_shape](const R& r) {
            std::size_t n = 1;
            for (auto d : grid_shape(r)) n *= static_cast<std::size_t>(d);
            return n;
        };
        // A solved sweep's (engine='kolmogorov'): values with their
        // discretisation errors, NaN where an interrupted sweep did not reach.
        auto solved_column = [grid_shape, grid_size](const R& r, auto get) {
            const double nan = std::numeric_limits<double>::quiet_NaN();
            EstimateSeries out;
            out.level = nan; // a solver's values have no intervals
            out.items.assign(grid_size(r), solved_estimate(nan, nan));
            for (std::size_t k = 0; k < r.points.size() && k < out.items.size(); ++k) out.items[k] = get(r.points[k]);
            out.shape = grid_shape(r);
            return out;
        };
        auto column = [grid_shape, grid_size](const R& r, auto get) {
            const double nan = std::numeric_limits<double>::quiet_NaN();
            std::vector<Estimate> v(grid_size(r), Estimate{nan, nan, nan, nan, r.request.level});
            for (std::size_t k = 0; k < r.points.size() && k < v.size(); ++k) v[k] = get(r.points[k]);
            EstimateSeries out = series(v, r.request.level);
            out.shape = grid_shape(r);
            return out;
        };
        // One axis's value at every point ('v': the swept constant, 't': tau,
        // 'n': noise), in the points' shape.
        auto grid_axis = [grid_shape, grid_size](const R& r, char axis) {
            const std::size_t nn = r.request.noises.size(), nt = r.request.taus.size();
            std::vector<double> v(grid_size(r));
            for (std::size_t k = 0; k < v.size(); ++k)
                v[k] = axis == 'n'   ? r.request.noises[k % nn]
                       : axis == 't' ? r.request.taus[(k / nn) % nt]
                                     : r.request.vary_values[k / (nn * nt)];
            return py::array_t<double>(to_array(v).attr("reshape")(grid_shape(r)));
        };
        // Every estimate a point declares (SweepPoint::fields, its sampled or
        // solved block inlined) as a column over the grid: sampled from the
        // point's estimates, solved from its solution; None where the sweep's
        // method has no such quantity.
        {
            using Get = std::function<Estimate(const SweepPoint&)>;
            struct Column {
                std::string name, doc;
                Get sampled, solved;
            };
            std::vector<Column> columns;
            const auto column_named = [&columns](const FieldInfo& f) -> Column& {
                const std::string name = field_flat_name(f);
                for (Column& each : columns)
                    if (each.name == name) return each;
                columns.push_back(Column{name, field_doc(f), nullptr, nullptr});
                return columns.back();
            };
            SweepPoint::fields([&](auto member, const FieldInfo& f) {
                using Value = std::remove_cvref_t<decltype(std::declval<SweepPoint>().*member)>;
                if constexpr (std::is_same_v<Value, Estimate>) {
                    Column& col = column_named(f);
                    col.sampled = [member](const SweepPoint& p) { return p.*member; };
                    col.solved = [member](const SweepPoint& p) { return solved_estimate((p.*member).value, (p.*member).error); };
                } else if constexpr (std::is_same_v<Value, LongExcursionEstimates>) {
                    LongExcursionEstimates::fields([&](auto inner, const FieldInfo& g) {
                        if constexpr (std::is_same_v<std::remove_cvref_t<decltype(std::declval<Value>().*inner)>, Estimate>)
                            column_named(g).sampled = [member, inner](const SweepPoint& p) { return (p.*member).*inner; };
                    });
                } else if constexpr (std::is_same_v<Value, std::optional<KolmogorovResult>>) {
                    KolmogorovResult::fields([&](auto inner, const FieldInfo& g) {
                        if constexpr (std::is_same_v<std::remove_cvref_t<decltype(std::declval<KolmogorovResult>().*inner)>, Estimate>)
                            column_named(g).solved = [member, inner](const SweepPoint& p) { return *(p.*member).*inner; };
                    });
                }
            });
            for (const Column& col : columns) {
                const std::string doc = col.doc + " per point (EstimateSeries, shape `shape`; NaN where an "
                                        "interrupted sweep did not reach; kind 'solved' with engine='kolmogorov'" +
                                        std::string(col.sampled ? "" : "; None for a sampled sweep") +
                                        (col.solved ? "" : "; None for a solved sweep") + ")";
                c.def_property_readonly(
                    col.name.c_str(),
                    [col, column, solved_column](const R& r) -> py::object {
                        if (r.solved()) return col.solved ? py::cast(solved_column(r, col.solved)) : py::none();
                        return col.sampled ? py::cast(column(r, col.sampled)) : py::none();
                    },
                    doc.c_str());
            }
        }
        c.def_property_readonly(
             "params", [](const R& r) { return r.request.params; },
             "friction, relaxation and bias of the sweep (Params; its noise and tau are placeholders)")
            .def_property_readonly(
                "noises", [](const R& r) { return to_array(r.request.noises); }, "the noise grid [m^2 s^-3], sorted")
            .def_property_readonly(
                "taus", [](const R& r) { return to_array(r.request.taus); }, "the tau grid [s], sorted")
            .def_property_readonly(
                "vary", [](const R& r) { return r.request.vary; },
                "the swept constant of the drift expression (vary=), '' when none")
            .def_property_readonly(
                "vary_values", [](const R& r) { return to_array(r.request.vary_values); },
                "the swept constant's values, sorted (empty without vary=)")
            .def_property_readonly(
                "shape", [grid_shape](const R& r) { return py::tuple(py::cast(grid_shape(r))); },
                "(len(taus), len(noises)), or (len(vary_values), len(taus), len(noises)) with vary=")
            .def_property_readonly(
                "varied",
                [grid_axis](const R& r) -> py::object {
                    if (!r.varies()) return py::none();
                    return grid_axis(r, 'v');
                },
                "the swept constant's value at every point (shape as `shape`), None without vary=")
            .def_property_readonly(
                "noise", [grid_axis](const R& r) { return grid_axis(r, 'n'); },
                "noise of every point [m^2 s^-3], shape `shape` (noises along the last axis)")
            .def_property_readonly(
                "tau", [grid_axis](const R& r) { return grid_axis(r, 't'); },
                "tau of every point [s], shape `shape` (taus along the axis before it)")
            .def_property_readonly(
                "method", [](const R& r) -> std::string { return r.solved() ? "kolmogorov" : "monte carlo"; },
                "'monte carlo', or 'kolmogorov' with engine='kolmogorov'")
            .def_property_readonly(
                "stop_rule",
                [](const R& r) {
                    std::vector<std::string> v;
                    for (const auto& p : r.points) v.push_back(p.stop_rule);
                    return v;
                },
                "stop rule used at every point (list of str)")
            .def_readonly("exponents", &R::exponents, "one SweepExponent per tau (with >= 2 noises), per value and tau with vary=")
            .def_readonly("white_limits", &R::white_limits,
                          "one SweepWhiteLimit per noise (with >= 2 taus > 0), per value and noise with vary=")
            .def_readonly("seconds", &R::seconds, "wall time [s]")
            .def_readonly("interrupted", &R::interrupted,
                          "True when the sweep was stopped early (Ctrl-C): only the points run so far are here")
            .def_readonly("resumed", &R::resumed, "excursions restored from a checkpoint (resume=)")
            .def("__repr__", [](const R& r) {
                return "SweepResult(" + (r.varies() ? r.request.vary + "=" + std::to_string(r.request.vary_values.size()) + " values, " : std::string()) + "taus=" + std::to_string(r.request.taus.size()) +
                       ", noises=" + std::to_string(r.request.noises.size()) +
                       (r.solved() ? std::string(", engine='kolmogorov' (discretisation errors))")
                                   : ", excursions=" + std::to_string(r.request.excursions) + " per point)");
            });

    }
}

} // namespace stickslip::python
