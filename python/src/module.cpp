// SPDX-License-Identifier: BSD-3-Clause
// The `stickslip._core` extension module: exceptions, parameters, estimates
// (here), the request structures and their run entry point (requests.cpp),
// the result classes (results.cpp) and the closed forms (analytic.cpp). The
// public, documented API is the pure-Python package `stickslip`
// (python/stickslip/__init__.py), which re-exports these classes and makes
// one keyword function per request from the requests' own settings.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "bindings.hpp"
#include "stickslip/kolmogorov.hpp"
#include "stickslip/number_text.hpp"
#include "stickslip/drift_input.hpp"
#include "stickslip/config.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/sample_runs.hpp"

namespace stickslip::python {

py::array_t<double> to_array(const std::vector<double>& v) {
    py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
    if (!v.empty()) std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
}

py::array_t<std::int64_t> to_array(const std::vector<int>& v) {
    py::array_t<std::int64_t> a(static_cast<py::ssize_t>(v.size()));
    auto* d = a.mutable_data();
    for (std::size_t k = 0; k < v.size(); ++k) d[k] = v[k];
    return a;
}

std::string setting_text(const py::handle& v) {
    if (PyBool_Check(v.ptr())) return v.ptr() == Py_True ? "True" : "False";
    if (PyFloat_Check(v.ptr())) return py::repr(v).cast<std::string>();
    if (PyLong_Check(v.ptr())) return py::str(v).cast<std::string>();
    if (PyUnicode_Check(v.ptr())) return v.cast<std::string>();
    if (py::hasattr(v, "ravel")) return setting_text(v.attr("ravel")().attr("tolist")()); // a NumPy array
    if (PyIndex_Check(v.ptr())) return py::str(py::int_(py::reinterpret_borrow<py::object>(v))).cast<std::string>();
    if (py::hasattr(v, "__float__") && !py::hasattr(v, "__len__"))
        return py::repr(py::float_(py::reinterpret_borrow<py::object>(v))).cast<std::string>();
    if (PyList_Check(v.ptr()) || PyTuple_Check(v.ptr())) {
        std::string s;
        for (const py::handle item : v) {
            if (!s.empty()) s += ',';
            s += setting_text(item);
        }
        return s.empty() ? std::string() : s;
    }
    return py::str(v).cast<std::string>();
}

py::object json_loads(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

std::string field_doc(const FieldInfo& f) {
    return std::string(f.help) + (*f.unit ? " [" + std::string(f.unit) + "]" : std::string());
}

std::vector<DeclaredStruct>& declared_structs() {
    static std::vector<DeclaredStruct> all;
    return all;
}

std::string float_repr(double x) {
    if (std::isinf(x)) return x > 0 ? "float('inf')" : "float('-inf')";
    return py::repr(py::float_(x)).cast<std::string>();
}

namespace {

/// Python exception types, created once (module state lives as long as the process).
PyObject* g_invalid_parameter = nullptr;
PyObject* g_untrustworthy = nullptr;
PyObject* g_capped = nullptr;

/// The model parameters' fields, in order: (name, unit, help, value).
struct ParamField {
    std::string name, unit, help;
    double value;
};

std::vector<ParamField> param_fields(ModelParams p) {
    std::vector<ParamField> out;
    // The numbers only; the drift law's settings are keywords of their own (params_with).
    visit_settings(p, [&](auto&& field, const SettingInfo& info) {
        if constexpr (std::is_same_v<std::decay_t<decltype(field)>, double>)
            out.push_back({info.name, info.unit, info.help, field});
    });
    return out;
}

/// drift= as Python gives it: an expression (str), two arrays (v, b) of a
/// table, or a callable b(v) (SI units), sampled here, once, on the knots the
/// library chooses for the model (a Python function is never called from a run).
void set_drift(ModelParams& p, const py::handle& value) {
    p.drift.clear();
    p.drift_table.clear();
    p.drift_table_v.clear();
    p.drift_table_b.clear();
    p.drift_function = nullptr;
    if (value.is_none()) return;
    if (py::isinstance<py::str>(value)) {
        parse_setting(SettingInfo{"drift", "", ""}, value.cast<std::string>(), TextValue{p.drift});
        return;
    }
    if (PyCallable_Check(value.ptr())) {
        const py::function f = py::reinterpret_borrow<py::function>(value);
        ModelParams q = p;
        q.drift_function = [f](double v) { return f(v).cast<double>(); };
        const DriftLaw law = make_drift_law(q);
        for (int k = 0; k < law.knots; ++k) {
            p.drift_table_v.push_back(law.knot(k));
            p.drift_table_b.push_back(law.values[k]);
        }
        return;
    }
    const char* forms = "drift must be an expression (str), a callable b(v) or two arrays (v, b)";
    if (!py::isinstance<py::sequence>(value)) throw InvalidParameter("drift", std::string(forms) + ", got " +
                                                                                  py::str(py::type::of(value)).cast<std::string>());
    const auto pair = value.cast<py::sequence>();
    if (pair.size() != 2) throw InvalidParameter("drift", forms);
    try {
        p.drift_table_v = pair[0].cast<std::vector<double>>();
        p.drift_table_b = pair[1].cast<std::vector<double>>();
    } catch (const py::cast_error&) {
        throw InvalidParameter("drift", "drift=(v, b): both must be sequences of numbers (m/s, m s^-2)");
    }
    // Two empty arrays left no law at all, and the affine default ran.
    if (p.drift_table_v.empty() && p.drift_table_b.empty())
        throw InvalidParameter("drift", "drift=(v, b) has no rows; a table needs at least two (drift=None: the "
                                        "affine law of relaxation and bias)");
}

/// `base` with the fields given as keywords changed (each read by the
/// library's parser, so a bad value gets the CLI's message), validated.
ModelParams params_with(ModelParams base, const py::kwargs& kw, const char* function) {
    // relaxation= or bias= beside a drift law would be dropped silently (the
    // law replaces them): refused, as the CLI refuses --relaxation with --drift.
    bool law_given = false;
    for (auto item : kw) {
        const auto key = item.first.cast<std::string>();
        if ((key == "drift" || key == "drift_table") && !item.second.is_none() &&
            !(py::isinstance<py::str>(item.second) && item.second.cast<std::string>().empty()))
            law_given = true;
    }
    for (auto item : kw) {
        const auto key = item.first.cast<std::string>();
        if ((key == "relaxation" || key == "bias") && (law_given || (base.has_drift_law() && !kw.contains("drift") &&
                                                                     !kw.contains("drift_table"))))
            throw InvalidParameter(key, key + " cannot be combined with a drift law, which gives the whole b(v): put "
                                              "the drag and the constant force into it (e.g. drift=\"0.342 - v/0.067\")");
    }
    for (auto item : kw) {
        const auto key = item.first.cast<std::string>();
        bool found = false;
        if (key == "drift") {
            set_drift(base, item.second);
            continue;
        }
        visit_settings(base, [&](auto&& field, const SettingInfo& info) {
            std::string name = info.name;
            std::replace(name.begin(), name.end(), '-', '_');
            if (key != name) return;
            found = true;
            parse_setting(info, setting_text(item.second), field);
        });
        if (!found) throw py::type_error(std::string(function) + " got an unexpected keyword argument '" + key + "'");
    }
    // A table file is read here, once: the Params hold its rows and digest
    // from then on (a file changed later changes no run made from them).
    if (kw.contains("drift_table")) {
        base.drift_table_v.clear();
        base.drift_table_b.clear();
        base.drift_table_digest.clear();
    }
    read_drift_inputs(base);
    validate(base);
    return base;
}

std::string params_repr(const ModelParams& p) {
    std::string out = "Params(";
    for (const auto& f : param_fields(p)) {
        // With a drift law, relaxation and bias are not the model's: show the law instead.
        if (p.has_drift_law() && (f.name == "relaxation" || f.name == "bias")) continue;
        out += (out.size() > 7 ? ", " : "") + f.name + "=" + float_repr(f.value);
    }
    if (!std::isnan(p.static_friction)) out += ", static_friction=" + float_repr(p.static_friction);
    if (!p.drift.empty()) out += ", drift=" + py::repr(py::str(p.drift)).cast<std::string>();
    if (!p.drift_params.empty()) out += ", drift_params=" + py::repr(py::str(p.drift_params)).cast<std::string>();
    if (!p.drift_table.empty()) out += ", drift_table=" + py::repr(py::str(p.drift_table)).cast<std::string>();
    if (!p.drift_table_v.empty() && p.drift_table.empty())
        out += ", drift=(<" + std::to_string(p.drift_table_v.size()) + " knots>)";
    if (p.has_drift_law()) out += ", knots=" + std::to_string(p.knots);
    return out + ")";
}

py::tuple params_tuple(const ModelParams& p) {
    py::list values;
    for (const auto& f : param_fields(p)) values.append(f.value);
    values.append(p.static_friction_level()); // unset and equal to the friction: the same model
    return py::tuple(values);
}

/// The docstring of Params: the model, then every field with its unit, range
/// and default, from the library's description of the settings.
const char* params_doc() {
    static std::string doc = [] {
        std::string d = R"doc(Physical parameters of the model, SI units (immutable).

    dV/dt + friction*sgn(V) = -V/relaxation + bias + sqrt(noise/2)*X(t),
    tau dX = -X dt + sqrt(2) dW,   E[X(0)X(t)] = exp(-|t|/tau)/tau.

As tau -> 0 the random force sqrt(noise/2)*X tends to a white noise of
intensity `noise` (<f(t)f(s)> = noise*delta(t-s)); tau = 0 is that white noise.
Keyword arguments only; relaxation=float('inf') means no viscous drag (then
|bias| < friction is needed for a stationary state).

)doc";
        std::string call = "Params(";
        for (const auto& f : param_fields(ModelParams{})) {
            call += (call.size() > 7 ? ", " : "") + f.name + "=" + float_repr(f.value);
            std::string line = "  " + f.name;
            line.resize(14, ' ');
            d += line + f.help + " [" + f.unit + "]\n";
        }
        d += "  static_friction  static friction Delta_s >= friction, or None (the default): equal to friction; a "
             "stuck object starts only when the force exceeds it, then slides against friction [m s^-2]\n";
        return call + ")\n\n" + d + "\nDefaults are the paper's Fig. 2 case. Invalid values raise\n"
                                    "InvalidParameterError (a ValueError) with the CLI's message.";
    }();
    return doc.c_str();
}

std::string estimate_repr(const Estimate& e) {
    if (e.kind != EstimateKind::Sampled)
        return "Estimate(value=" + float_repr(e.value) + ", error=" + float_repr(e.error) + ", kind='" +
               to_string(e.kind) + "')";
    return "Estimate(value=" + float_repr(e.value) + ", stderr=" + float_repr(e.error) + ", ci=(" +
           float_repr(e.lo) + ", " + float_repr(e.hi) + "), level=" + float_repr(e.level) + ")";
}

/// As the CLI's JSON writes it: {value, error, kind} and, when sampled, ci and level.
py::dict estimate_dict(const Estimate& e) {
    py::dict d;
    d["value"] = e.value;
    d["error"] = e.error;
    if (e.kind == EstimateKind::Sampled) {
        d["ci"] = py::make_tuple(e.lo, e.hi);
        d["level"] = e.level;
    }
    d["kind"] = to_string(e.kind);
    return d;
}

template <class Series, class Get>
py::array_t<double> series_column(const Series& s, Get get) {
    py::array_t<double> a(static_cast<py::ssize_t>(s.items.size()));
    auto* d = a.mutable_data();
    for (std::size_t k = 0; k < s.items.size(); ++k) d[k] = get(s.items[k]);
    if (!s.shape.empty()) return a.reshape(s.shape);
    return a;
}

/// `head` (the class's name and first fields), then the first and last values
/// and ")": the repr of a series.
template <class Series>
std::string series_repr(std::string head, const Series& s) {
    if (!s.items.empty()) {
        head += ", value=[" + float_repr(s.items.front().value);
        if (s.items.size() > 2) head += ", ...";
        if (s.items.size() > 1) head += ", " + float_repr(s.items.back().value);
        head += "]";
    }
    return head + ")";
}

/// A series' access: shape, len(s), s[k] and
/// s[i, j] (a 2-D series: a sweep's (tau, noise), row-major; s[h, i, j] when
/// it sweeps a drift constant too), np.asarray(s)
/// (the values). `name` is the class's name in the index errors.
template <class Series>
void add_series_access(py::class_<Series>& c, const std::string& name) {
    auto value = [](const auto& e) { return e.value; };
    c.def_property_readonly(
         "shape",
         [](const Series& s) {
             py::tuple t(s.shape.empty() ? 1 : s.shape.size());
             if (s.shape.empty()) t[0] = py::int_(s.items.size());
             for (std::size_t k = 0; k < s.shape.size(); ++k) t[k] = py::int_(s.shape[k]);
             return t;
         },
         "the arrays' shape: (n,), or (n_tau, n_noise) for a sweep ((n_vary, n_tau, n_noise) with vary=)")
        .def("__len__", [](const Series& s) { return s.items.size(); })
        .def("__getitem__",
             [name](const Series& s, py::tuple index) {
                 if (s.shape.size() < 2 || index.size() != s.shape.size())
                     throw py::index_error(name + " takes one index per axis, (i, j) or (h, i, j), only when "
                                                  "2-D or 3-D (it is " +
                                           std::to_string(std::max<std::size_t>(1, s.shape.size())) + "-D)");
                 py::ssize_t flat = 0;
                 for (std::size_t a = 0; a < s.shape.size(); ++a) {
                     const auto i = index[a].cast<py::ssize_t>();
                     if (i < 0 || i >= s.shape[a]) throw py::index_error(name + " index out of range");
                     flat = flat * s.shape[a] + i;
                 }
                 return s.items[static_cast<std::size_t>(flat)];
             })
        .def("__getitem__",
             [name](const Series& s, py::ssize_t k) {
                 const auto n = static_cast<py::ssize_t>(s.items.size());
                 if (k < 0) k += n;
                 if (k < 0 || k >= n) throw py::index_error(name + " index out of range");
                 return s.items[static_cast<std::size_t>(k)];
             })
        .def(
            "__array__",
            [value](const Series& s, const py::object& dtype) {
                py::array a = series_column(s, value);
                if (!dtype.is_none()) a = a.attr("astype")(dtype);
                return a;
            },
            py::arg("dtype") = py::none());
}

} // namespace

void raise_untrustworthy(const std::string& what, py::object result) {
    py::object exc = py::reinterpret_borrow<py::object>(g_untrustworthy)(what);
    exc.attr("result") = std::move(result);
    PyErr_SetObject(g_untrustworthy, exc.ptr());
    throw py::error_already_set();
}

void bind_core(py::module_& m) {
    // ---- exceptions -------------------------------------------------------------
    g_invalid_parameter = PyErr_NewExceptionWithDoc(
        "stickslip.InvalidParameterError",
        "Invalid input (a ValueError). str(e) is '--<parameter>: <message>', exactly what the\n"
        "`stickslip` command prints after 'stickslip: error: '; e.parameter names the parameter\n"
        "(as spelled on the command line, e.g. 'friction', 'dt', 'stop-rule') and e.message is\n"
        "the message alone.",
        PyExc_ValueError, nullptr);
    g_untrustworthy = PyErr_NewExceptionWithDoc(
        "stickslip.UntrustworthyResultError",
        "The run finished but its numbers cannot be believed, and none are returned (a\n"
        "RuntimeError; the command's exit status 3): excursions hit the runaway guard\n"
        "(CappedExcursionsError), every excursion ended within its first step, or an estimate is\n"
        "not a finite number. str(e) says why and what to change.",
        PyExc_RuntimeError, nullptr);
    g_capped = PyErr_NewExceptionWithDoc(
        "stickslip.CappedExcursionsError",
        "Some excursions hit the runaway guard (max_steps): the result would be biased and is\n"
        "not returned (an UntrustworthyResultError). Pass allow_capped=True to get it anyway,\n"
        "with a warning.",
        g_untrustworthy, nullptr);
    m.add_object("InvalidParameterError", py::handle(g_invalid_parameter));
    m.add_object("UntrustworthyResultError", py::handle(g_untrustworthy));
    m.add_object("CappedExcursionsError", py::handle(g_capped));
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const InvalidParameter& e) {
            const std::string text = "--" + e.parameter() + ": " + e.what();
            py::object exc = py::reinterpret_borrow<py::object>(g_invalid_parameter)(text);
            exc.attr("parameter") = e.parameter();
            exc.attr("message") = std::string(e.what());
            PyErr_SetObject(g_invalid_parameter, exc.ptr());
        } catch (const CappedExcursions& e) {
            PyErr_SetString(g_capped, e.what());
        } catch (const UntrustworthyResult& e) {
            PyErr_SetString(g_untrustworthy, e.what());
        } catch (const RunCancelled& e) {
            PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
        }
    });

    m.attr("__version__") = STICKSLIP_VERSION_STRING;

    // ---- Scales ---------------------------------------------------------------------
    py::class_<Scales> scales(m, "Scales", "Units of the nondimensional system (friction = noise = 1), in SI.");
    bind_fields<Scales>(scales, "Scales", "");
    scales
        .def("to_dict",
             [](const Scales& s) {
                 py::dict d;
                 Scales::fields([&](auto member, const FieldInfo& f) { d[f.name] = s.*member; });
                 return d;
             })
        .def("__repr__", [](const Scales& s) {
            return "Scales(time=" + float_repr(s.time) + ", length=" + float_repr(s.length) +
                   ", velocity=" + float_repr(s.velocity) + ", acceleration=" + float_repr(s.acceleration) +
                   ", diffusivity=" + float_repr(s.diffusivity) + ", noise_level=" + float_repr(s.noise_level) + ")";
        });

    // ---- Params -----------------------------------------------------------------------
    py::class_<ModelParams> params(m, "Params", params_doc());
    params.def(py::init([](const py::kwargs& kw) { return params_with(ModelParams{}, kw, "Params()"); }));
    for (const auto& f : param_fields(ModelParams{})) {
        const std::string name = f.name;
        params.def_property_readonly(
            name.c_str(),
            [name](const ModelParams& p) {
                for (const auto& g : param_fields(p))
                    if (g.name == name) return g.value;
                return 0.0;
            },
            (f.help + " [" + f.unit + "]").c_str());
    }
    params.def_property_readonly(
        "static_friction",
        [](const ModelParams& p) -> py::object {
            return std::isnan(p.static_friction) ? py::object(py::none()) : py::object(py::float_(p.static_friction));
        },
        "static friction Delta_s [m s^-2]: a stuck object starts only when the force exceeds it, then slides "
        "against friction; None: equal to friction");
    params        .def_property_readonly("force_amplitude", &ModelParams::force_amplitude,
                               "amplitude a = sqrt(noise/2) of the random force a*X [m s^-2 per s^-1/2]")
        .def_property_readonly("white", &ModelParams::white, "True for white noise (tau = 0)")
        .def_property_readonly("upper_threshold", &ModelParams::upper_threshold,
                               "x* = (Delta_s - b(0))/a [s^-1/2], Delta_s the static friction (friction unless "
                               "set): a stuck object starts moving up when X > x*")
        .def_property_readonly("lower_threshold", &ModelParams::lower_threshold,
                               "x-* = (-Delta_s - b(0))/a [s^-1/2]")
        .def_property_readonly("has_stationary_state", &has_stationary_state,
                               "False only without drag (relaxation inf) and |bias| >= friction")
        .def("nondimensional", &to_nondimensional,
             "The same system in units friction = noise = 1: Params(friction=1, noise=1, tau=tau/T, "
             "relaxation=relaxation/T, bias=bias/friction) with T = noise/friction^2 (see scales()).")
        .def("scales", &scales_of, "Units of the nondimensional system, in SI (a Scales).")
        .def_property_readonly(
            "drift", [](const ModelParams& p) -> py::object {
                if (!p.drift.empty()) return py::str(p.drift);
                if (!p.drift_table_v.empty()) return py::make_tuple(p.drift_table_v, p.drift_table_b);
                return py::none();
            },
            "the drift law b(v) when one replaces relaxation and bias: the expression (str), or the (v, b) "
            "knots a callable or arrays were sampled on; None for the affine law")
        .def_property_readonly("knots", [](const ModelParams& p) { return p.knots; },
                               "knots of the drift law's interpolant")
        .def_static(
            "from_nondimensional",
            [](const ModelParams& nd, const py::object& friction, const py::object& noise) {
                py::kwargs units;
                units["friction"] = friction;
                units["noise"] = noise;
                const ModelParams given = params_with(ModelParams{}, units, "from_nondimensional()");
                const ModelParams p = from_nondimensional(nd, given.friction, given.noise);
                validate(p);
                return p;
            },
            py::arg("nd"), py::arg("friction"), py::arg("noise"),
            "Inverse of nondimensional(): the SI parameters with the given friction [m s^-2] and noise "
            "[m^2 s^-3] whose nondimensional form is `nd`.")
        .def(
            "replace", [](const ModelParams& p, const py::kwargs& kw) { return params_with(p, kw, "replace()"); },
            "A copy with some fields changed: p.replace(tau=0.125).")
        .def(
            "to_dict",
            [](const ModelParams& p) {
                py::dict d;
                for (const auto& f : param_fields(p)) d[py::str(f.name)] = f.value;
                if (!std::isnan(p.static_friction)) d["static_friction"] = p.static_friction; // set only
                return d;
            },
            "The fields as a dict of floats (Params(**d) gives it back); static_friction only when set.")
        .def("__repr__", &params_repr)
        .def("__eq__",
             [](const ModelParams& a, const py::object& other) -> py::object {
                 if (!py::isinstance<ModelParams>(other)) return py::reinterpret_borrow<py::object>(Py_NotImplemented);
                 return py::bool_(params_tuple(a).equal(params_tuple(other.cast<const ModelParams&>())));
             })
        .def("__hash__", [](const ModelParams& p) { return py::hash(params_tuple(p)); });

    // ---- Estimate ----------------------------------------------------------------------
    py::class_<Estimate>(m, "Estimate",
                         "A value with its uncertainty and the kind that says what the uncertainty is, from every "
                         "method. kind 'sampled' (Monte Carlo): error is the standard error (also stderr), and "
                         "[lo, hi] the two-sided interval at `level`: value -+ q*stderr, or for D and D_t the "
                         "relative-error interval value/(1 +- q*stderr/value), never negative (hi = inf when "
                         "q*stderr >= value). kind 'solved' (engine='kolmogorov', a quadrature): error is the "
                         "estimated discretisation error (absolute; NaN when not estimated), no interval (NaN). "
                         "kind 'exact' (a closed form): error 0. float(e) is e.value.")
        .def_readonly("value", &Estimate::value)
        .def_property_readonly(
            "stderr",
            [](const Estimate& e) {
                return e.kind == EstimateKind::Sampled ? e.error : std::numeric_limits<double>::quiet_NaN();
            },
            "the standard error (NaN unless kind is 'sampled')")
        .def_readonly("error", &Estimate::error,
                      "the uncertainty, in the value's unit: the standard error (sampled), the estimated "
                      "discretisation error (solved) or 0 (exact)")
        .def_property_readonly("kind", [](const Estimate& e) { return to_string(e.kind); },
                               "'sampled', 'solved' or 'exact': what error means")
        .def_readonly("lo", &Estimate::lo)
        .def_readonly("hi", &Estimate::hi)
        .def_readonly("level", &Estimate::level)
        .def_property_readonly("ci", [](const Estimate& e) { return py::make_tuple(e.lo, e.hi); },
                               "(lo, hi): the confidence interval at `level`")
        .def("to_dict", &estimate_dict, "{'value', 'error', 'ci': (lo, hi), 'level', 'kind'}: as in the CLI's JSON")
        .def("__float__", [](const Estimate& e) { return e.value; })
        .def("__repr__", &estimate_repr);

    // The Kolmogorov engine's values were a class of their own until every
    // estimate carried its kind: the old name stays, for isinstance checks.
    m.attr("GridEstimate") = m.attr("Estimate");

    py::class_<EstimateSeries> series(m, "EstimateSeries",
                               "Estimates of one kind along an axis (bins, lags, times, sweep points), as NumPy "
                               "arrays: value, error, stderr, lo, hi (shape (n,)) and ci (shape (n, 2)); a sweep's "
                               "are 2-D (n_tau, n_noise). kind 'sampled': error is the standard errors, [lo, hi] "
                               "the intervals at `level`. kind 'solved' (engine='kolmogorov'): error is the "
                               "estimated discretisation errors; stderr, lo, hi and level NaN. np.asarray(s) is "
                               "s.value; s[k] is the k-th Estimate (in flat order), s[i, j] that of a 2-D series.");
    series
        .def_property_readonly("value", [](const EstimateSeries& s) {
            return series_column(s, [](const Estimate& e) { return e.value; });
        })
        .def_property_readonly("stderr", [](const EstimateSeries& s) {
            return series_column(s, [](const Estimate& e) {
                return e.kind == EstimateKind::Sampled ? e.error : std::numeric_limits<double>::quiet_NaN();
            });
        }, "the standard errors (NaN unless kind is 'sampled')")
        .def_property_readonly("error", [](const EstimateSeries& s) {
            return series_column(s, [](const Estimate& e) { return e.error; });
        }, "the uncertainties: the standard errors (sampled) or the estimated discretisation errors (solved)")
        .def_property_readonly("kind", [](const EstimateSeries& s) { return to_string(s.kind()); },
                               "'sampled' or 'solved': what error means")
        .def_property_readonly("lo", [](const EstimateSeries& s) {
            return series_column(s, [](const Estimate& e) { return e.lo; });
        })
        .def_property_readonly("hi", [](const EstimateSeries& s) {
            return series_column(s, [](const Estimate& e) { return e.hi; });
        })
        .def_property_readonly("ci",
                               [](const EstimateSeries& s) {
                                   py::array_t<double> a({static_cast<py::ssize_t>(s.items.size()), py::ssize_t{2}});
                                   auto r = a.mutable_unchecked<2>();
                                   for (std::size_t k = 0; k < s.items.size(); ++k) {
                                       r(static_cast<py::ssize_t>(k), 0) = s.items[k].lo;
                                       r(static_cast<py::ssize_t>(k), 1) = s.items[k].hi;
                                   }
                                   if (s.shape.empty()) return a;
                                   std::vector<py::ssize_t> shape = s.shape;
                                   shape.push_back(2);
                                   return py::array_t<double>(a.reshape(shape));
                               },
                               "shape (n, 2), or the series' shape + (2,): the intervals [lo, hi]");
    add_series_access(series, "EstimateSeries");
    series.def_readonly("level", &EstimateSeries::level)
        .def("to_dict",
             [](const EstimateSeries& s) {
                 py::dict d;
                 d["value"] = series_column(s, [](const Estimate& e) { return e.value; });
                 d["error"] = series_column(s, [](const Estimate& e) { return e.error; });
                 if (s.kind() == EstimateKind::Sampled) { // a solver has no intervals
                     d["lo"] = series_column(s, [](const Estimate& e) { return e.lo; });
                     d["hi"] = series_column(s, [](const Estimate& e) { return e.hi; });
                     d["level"] = s.level;
                 }
                 d["kind"] = to_string(s.kind());
                 return d;
             },
             "{'value', 'error'} arrays and 'kind'; sampled, also the 'lo', 'hi' arrays and 'level'")
        .def("__repr__", [](const EstimateSeries& s) {
            const std::string n = "EstimateSeries(n=" + std::to_string(s.items.size());
            return series_repr(s.kind() == EstimateKind::Sampled ? n + ", level=" + float_repr(s.level)
                                                                 : n + ", kind='" + to_string(s.kind()) + "'",
                               s);
        });
    // A solved series was a class of its own until estimates carried their
    // kind: the old name stays, for isinstance checks.
    m.attr("GridEstimateSeries") = m.attr("EstimateSeries");

}

} // namespace stickslip::python

PYBIND11_MODULE(_core, m) {
    m.doc() = "stickslip._core: the compiled part of the stickslip package (use `import stickslip`).";
    stickslip::python::bind_core(m);
    stickslip::python::bind_results(m);
    stickslip::python::bind_requests(m);
    stickslip::python::bind_analytic(m);
    stickslip::python::bind_pickling(m); // last: it adds to the classes bound above
    // For python/tools/make_stubs.py and make_schema.py: the results that declare
    // their fields (result_fields.hpp), as the bindings above recorded them.
    m.def(
        "_result_fields",
        [] {
            pybind11::list out;
            for (const auto& d : stickslip::python::declared_structs()) {
                pybind11::dict one;
                one["python_class"] = d.python_class;
                one["schema_definition"] = d.schema_definition;
                pybind11::list fields;
                for (const auto& f : d.fields) {
                    pybind11::dict each;
                    const char* keys[] = {"name", "unit", "help", "type", "form", "json", "key"};
                    for (std::size_t k = 0; k < f.size(); ++k) each[keys[k]] = f[k];
                    fields.append(each);
                }
                one["fields"] = fields;
                out.append(one);
            }
            return out;
        },
        "The result structs that declare their fields, with each field's name, unit, help, Python type and "
        "form (for the stub and schema generators).");
}
