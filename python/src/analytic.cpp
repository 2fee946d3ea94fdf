// SPDX-License-Identifier: BSD-3-Clause
// Exact white-noise references from Python (analytic.hpp, fokker_planck.hpp,
// white_noise.hpp). The functions here take flat float64 arrays of equal
// length; broadcasting and shapes are handled by stickslip/analytic.py.
#include <cmath>
#include <limits>

#include "bindings.hpp"
#include "stickslip/analytic.hpp"
#include "stickslip/drift_law_quadrature.hpp"
#include "stickslip/fokker_planck.hpp"
#include "stickslip/number_text.hpp"
#include "stickslip/report.hpp"
#include "stickslip/white_noise.hpp"

namespace stickslip::python {

namespace {

using Flat = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// out[k] = f(k) for k < n, computed without the GIL.
template <class F>
py::array_t<double> fill(py::ssize_t n, F f) {
    py::array_t<double> out(n);
    double* d = out.mutable_data();
    {
        py::gil_scoped_release nogil;
        for (py::ssize_t k = 0; k < n; ++k) d[k] = f(k);
    }
    return out;
}

void same_length(const Flat& a, const Flat& b) {
    if (a.ndim() != 1 || b.ndim() != 1 || a.size() != b.size())
        throw std::invalid_argument("internal: flat arrays of equal length expected");
}

std::vector<double> to_vector(const Flat& a) { return std::vector<double>(a.data(), a.data() + a.size()); }

py::array_t<double> rows_to_array(const std::vector<std::vector<double>>& rows, std::size_t cols) {
    py::array_t<double> a({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(cols)});
    auto r = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (std::size_t j = 0; j < cols; ++j)
            r(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(j)) =
                rows[i].empty() ? std::numeric_limits<double>::quiet_NaN() : rows[i][j];
    return a;
}

} // namespace

void bind_analytic(py::module_& m) {
    // ---- Hayakawa's stationary density ---------------------------------------------------
    m.def("_hayakawa_density", [](const ModelParams& p, const Flat& v) {
        if (p.has_drift_law()) { // the stationary density of any law, by its quadrature
            const DriftLawWhiteNoise law(p);
            const double* x = v.data();
            return fill(v.size(), [&](py::ssize_t k) { return law.density(x[k]); });
        }
        const HayakawaDensity h(p);
        const double* x = v.data();
        return fill(v.size(), [&](py::ssize_t k) { return h(x[k]); });
    });
    m.def("_hayakawa_potential", [](const ModelParams& p, const Flat& v) {
        const HayakawaDensity h(p);
        const double* x = v.data();
        return fill(v.size(), [&](py::ssize_t k) { return h.potential(x[k]); });
    });
    m.def("_hayakawa_probability", [](const ModelParams& p, const Flat& a, const Flat& b) {
        same_length(a, b);
        if (p.has_drift_law()) {
            const DriftLawWhiteNoise law(p);
            const double *x = a.data(), *y = b.data();
            return fill(a.size(), [&](py::ssize_t k) {
                return x[k] <= y[k] ? law.probability(x[k], y[k]) : -law.probability(y[k], x[k]);
            });
        }
        const HayakawaDensity h(p);
        const double *x = a.data(), *y = b.data();
        return fill(a.size(), [&](py::ssize_t k) { return h.probability(x[k], y[k]); });
    });
    m.def("_hayakawa_moments", [](const ModelParams& p) {
        const HayakawaDensity h(p);
        py::dict d;
        d["mean"] = h.mean();
        d["variance"] = h.variance();
        d["mode"] = h.mode();
        return d;
    });

    // ---- stationary references --------------------------------------------------------------
    m.def("_white_noise_reference", [](const ModelParams& p) {
        WhiteNoiseReference r{};
        {
            py::gil_scoped_release nogil;
            r = white_noise_reference(p);
        }
        py::dict d;
        d["mobility"] = r.mobility;
        d["diffusivity"] = r.diffusivity;
        d["variance"] = r.variance;
        return d;
    });
    m.def("_dry_friction_mobility", &dry_friction_mobility);
    m.def("_dry_friction_diffusivity", &dry_friction_diffusivity);
    m.def("_viscous_diffusivity", &viscous_diffusivity);
    m.def("_is_pure_dry_friction", &is_pure_dry_friction);

    // ---- pure dry friction closed forms (Touchette, Van der Straeten, Just 2010) ---------------
    m.def("_first_moment", [](const ModelParams& p, const Flat& t, const Flat& v0) {
        same_length(t, v0);
        const double *x = t.data(), *y = v0.data();
        return fill(t.size(), [&](py::ssize_t k) { return dry_friction_first_moment(p, x[k], y[k]); });
    });
    m.def("_autocorrelation", [](const ModelParams& p, const Flat& t) {
        const double* x = t.data();
        return fill(t.size(), [&](py::ssize_t k) { return dry_friction_autocorrelation(p, x[k]); });
    });
    m.def("_propagator", [](const ModelParams& p, const Flat& v, const Flat& t, const Flat& v0) {
        same_length(v, t);
        same_length(v, v0);
        const double *x = v.data(), *s = t.data(), *y = v0.data();
        return fill(v.size(), [&](py::ssize_t k) { return dry_friction_propagator(p, x[k], s[k], y[k]); });
    });

    // ---- Fokker-Planck solutions (any drift) -----------------------------------------------------
    py::class_<WhiteNoiseFokkerPlanck>(m, "FokkerPlanck",
                                      "Fokker-Planck solver of the white-noise velocity diffusion for any drift "
                                      "(finite volumes, Richardson extrapolation, Crank-Nicolson; see "
                                      "fokker_planck.hpp). Built once per parameter set; queries take 1-D arrays of "
                                      "times [s] and velocities [m/s]. params.tau is ignored.")
        .def(py::init([](const ModelParams& p, int cells, double half_width, int steps_per_unit_time, bool richardson) {
                 FokkerPlanckSettings s;
                 s.cells = cells;
                 s.half_width = half_width;
                 s.steps_per_unit_time = steps_per_unit_time;
                 s.richardson = richardson;
                 py::gil_scoped_release nogil;
                 return new WhiteNoiseFokkerPlanck(p, s);
             }),
             py::arg("params"), py::arg("cells") = 4000, py::arg("half_width") = 0.0,
             py::arg("steps_per_unit_time") = 1000, py::arg("richardson") = true)
        .def("first_moment",
             [](const WhiteNoiseFokkerPlanck& fp, double v0, const Flat& t) {
                 const auto times = to_vector(t);
                 std::vector<double> r;
                 {
                     py::gil_scoped_release nogil;
                     r = fp.first_moment(v0, times);
                 }
                 return to_array(r);
             })
        .def("autocorrelation",
             [](const WhiteNoiseFokkerPlanck& fp, const Flat& t) {
                 const auto times = to_vector(t);
                 std::vector<double> r;
                 {
                     py::gil_scoped_release nogil;
                     r = fp.autocorrelation(times);
                 }
                 return to_array(r);
             })
        .def("density",
             [](const WhiteNoiseFokkerPlanck& fp, double v0, const Flat& t, const Flat& v) {
                 const auto times = to_vector(t);
                 const auto vs = to_vector(v);
                 std::vector<std::vector<double>> r;
                 {
                     py::gil_scoped_release nogil;
                     r = fp.density(v0, times, vs);
                 }
                 return rows_to_array(r, vs.size());
             })
        .def_property_readonly("cell_width", &WhiteNoiseFokkerPlanck::cell_width)
        .def_property_readonly("lower_velocity", &WhiteNoiseFokkerPlanck::lower_velocity)
        .def_property_readonly("upper_velocity", &WhiteNoiseFokkerPlanck::upper_velocity);

    // ---- everything `stickslip analytic` prints ---------------------------------------------------
    using R = WhiteNoiseResult;
    py::class_<R> c(m, "WhiteNoiseResult",
                    "Exact white-noise references for one parameter set (stickslip.analytic.white_noise): what "
                    "`stickslip analytic` prints. to_dict() is the CLI's JSON.");
    add_renderings<R>(c);
    add_declared_fields(c, [](const R& r) -> const WhiteNoiseReference& { return r.reference; });
    note_declared<WhiteNoiseReference>("WhiteNoiseResult", "merged:white_noise_reference_report");
    bind_fields<R>(c, "WhiteNoiseResult", "merged:white_noise_reference_report"); // the series
    c.def_property_readonly("params", [](const R& r) { return r.request.params; })
        .def_property_readonly("times", [](const R& r) { return to_array(r.request.times); },
                               "t [s], shape (n,): the request's times (the same as `time`)")
        .def_property_readonly("v0", [](const R& r) { return r.request.v0; }, "initial velocity [m/s]")
        .def_property_readonly(
            "velocities", [](const R& r) { return to_array(r.request.velocities); }, "v [m/s], shape (m,)")
        .def_property_readonly(
            "stationary_density", [](const R& r) { return to_array(r.stationary_density); },
            "Hayakawa's p(v) [s/m], shape (m,)")
        .def_property_readonly(
            "transient_density",
            [](const R& r) { return rows_to_array(r.transient_density, r.request.velocities.size()); },
            "p(v, t | v0) [s/m], shape (n, m); rows at t = 0 (a delta function) are NaN")
        .def_property_readonly(
            "method", [](const R& r) { return r.grid().solver; }, "'closed form (...)' or 'fokker-planck (...)'")
        .def("__repr__", [](const R& r) {
            using number_text::general;
            return "WhiteNoiseResult(mobility=" + general(r.reference.mobility) + " m/s, diffusivity=" +
                   general(r.reference.diffusivity) + " m^2/s, variance=" + general(r.reference.variance) +
                   " m^2/s^2, times=" + std::to_string(r.request.times.size()) +
                   ", velocities=" + std::to_string(r.request.velocities.size()) + ")";
        });
}

} // namespace stickslip::python
