// SPDX-License-Identifier: BSD-3-Clause
// Pickling of every class the module returns (results, their parts, Params,
// the requests), by one mechanism: a value's state is its C++ members as
// plain Python objects (float, int, bool, bytes, None, lists and tuples;
// columns of numbers as NumPy arrays), nested as the structs nest, written
// and read by the same per-struct list of members (fields() below). Floats
// stay doubles, so a round trip gives the same bits; nothing in the state
// depends on the machine (no pointers; an array's dtype records its byte
// order). The state is tagged with the module's version and refused by any
// other version: the format follows the library's structs and is not stable
// across versions (pickles are for multiprocessing, joblib and caches, not
// for archives: save() writes those).
//
// A struct's members are listed once, in fields(f, x) (or, for a result
// that declares its fields, result_fields.hpp, by that declaration): f(member, ...) either
// appends each member's state (Save) or reads it back (Load). The requests'
// settings are not listed: visit_settings (setting.hpp) already names every
// one, so a new setting is pickled without a change here; only their members
// that are not settings are.
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "stickslip/bruteforce.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/kolmogorov.hpp"
#include "stickslip/observables.hpp"
#include "stickslip/spectrum.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/white_noise.hpp"

namespace stickslip::python {

namespace {

// ---- the members of every pickled struct ----------------------------------------------------

/// A struct that declares its fields (result_fields.hpp): every one of them,
/// in declaration order.
template <class F, DeclaredFields T> void declared_fields(F& f, T& x) {
    T::fields([&](auto member, const FieldInfo&) { f(x.*member); });
}
template <class F, DeclaredFields T> void fields(F& f, T& x) { declared_fields(f, x); }

// A struct that declares its fields and holds more: what it does not declare,
// then the declared fields (so that a new one is pickled without a line here).

template <class F> void fields(F& f, Estimate& x) { f(x.value, x.error, x.lo, x.hi, x.level, x.kind); }
template <class F> void fields(F& f, EstimateSeries& x) { f(x.items, x.level, x.shape); }
template <class F> void fields(F& f, ResolvedEngine& x) {
    f(x.stop_rule, x.lattice_step, x.lattice_offset, x.lattice_bound, x.lattice_points, x.truncated_mass, x.jump_rate,
      x.white_level, x.upper_threshold, x.lower_threshold);
}
template <class F> void fields(F& f, RunTotals& x) {
    f(x.sums, x.moments, x.requested, x.threads, x.interrupted, x.control_variate);
    declared_fields(f, x);
}
template <class F> void fields(F& f, MonteCarloDetails& x) { f(x.engine, x.totals); }
template <class F> void fields(F& f, GridDetails& x) {
    f(x.solver, x.cells, x.lower, x.upper, x.discretisation_error);
}
template <class F> void fields(F& f, MethodResult& x) { f(x.details); }
template <class F> void fields(F& f, KolmogorovGrid& x) {
    f(x.lower_threshold, x.upper_threshold, x.x_spacing, x.band_intervals, x.band_first, x.x_nodes, x.v_lower,
      x.v_upper, x.v_cells_neg, x.v_cells_pos, x.v_stretch, x.v_grading, x.lattice_step, x.lattice_bound,
      x.graded_x_lower, x.graded_x_upper);
}
template <class F> void fields(F& f, KolmogorovGridSolution& x) {
    f(x.grid, x.states, x.lu_nonzeros, x.diffusivity, x.diffusivity_x, x.mobility, x.velocity_variance,
      x.stuck_probability, x.mean_duration, x.tail_mass,
      x.seconds, x.velocity_faces, x.velocity_density);
}
template <class F> void fields(F& f, KolmogorovResult& x) {
    f(static_cast<MethodResult&>(x), x.params, x.velocity_variance, x.diffusivity_x, x.levels, x.converged,
      x.interrupted, x.note, x.seconds);
    declared_fields(f, x);
}
template <class F> void fields(F& f, SamplePath& x) { f(x.t, x.x, x.mode, x.v, x.u); }
template <class F> void fields(F& f, SweepPoint& x) {
    f(x.warnings);
    declared_fields(f, x);
}

/// The model: its settings, and the law's knots given as arrays (a callable
/// is sampled on them when given, so it is not needed afterwards).
template <class F> void fields(F& f, ModelParams& x) {
    visit_settings(x, [&](auto&& setting, const SettingInfo&) { f(setting); });
    f(x.drift_table_v, x.drift_table_b, x.drift_table_digest);
}

/// A request: the whole model first (some requests leave parts of it out of
/// their settings, e.g. analytic's tau, a sweep's noise and tau, which the
/// reports still give), every setting (visit_settings; the model's again,
/// harmlessly), then what is not a setting.
template <class Request>
concept RunRequest = std::is_base_of_v<RunSettings, Request>;
template <class F, RunRequest R> void fields(F& f, R& x) {
    f(x.params);
    visit_settings(x, [&](auto&& setting, const SettingInfo&) { f(setting); });
    f(x.command_line, x.control.first_index);
}
template <class F> void fields(F& f, WhiteNoiseRequest& x) {
    f(x.params);
    visit_settings(x, [&](auto&& setting, const SettingInfo&) { f(setting); });
    f(x.command_line);
}

template <class F> void fields(F& f, DiffusivityResult& x) {
    f(static_cast<MethodResult&>(x), x.request, x.estimates, x.precision, x.warnings, x.discretisation, x.knots_check,
      x.solution, x.control_variate);
}
template <class F> void fields(F& f, BruteForceResult& x) {
    f(static_cast<MethodResult&>(x), x.request, x.estimates, x.start_noise, x.warnings);
}
template <class F> void fields(F& f, DensityResult& x) {
    f(static_cast<MethodResult&>(x), x.request, x.histogram, x.estimates, x.warnings, x.solution);
    declared_fields(f, x);
}
template <class F> void fields(F& f, CorrelationResult& x) {
    f(static_cast<MethodResult&>(x), x.request, x.estimates, x.warnings);
    declared_fields(f, x);
}
template <class F> void fields(F& f, MomentsResult& x) {
    f(static_cast<MethodResult&>(x), x.request, x.density, x.warnings);
    declared_fields(f, x);
}
template <class F> void fields(F& f, TrajectoryResult& x) {
    f(x.request, x.resolved, x.paths, x.excursion, x.warnings);
}
template <class F> void fields(F& f, SweepResult& x) {
    f(x.request, x.points, x.exponents, x.white_limits, x.seconds, x.interrupted, x.resumed, x.warnings);
}
template <class F> void fields(F& f, SpectrumResult& x) {
    f(static_cast<MethodResult&>(x), x.request, x.solution, x.reference, x.estimates, x.warnings);
    declared_fields(f, x);
}
template <class F> void fields(F& f, WhiteNoiseResult& x) {
    f(static_cast<MethodResult&>(x), x.request, x.reference, x.stationary_density, x.transient_density, x.warnings);
    declared_fields(f, x);
}

// ---- writing and reading a state ------------------------------------------------------------

template <class T> struct is_vector : std::false_type {};
template <class T, class A> struct is_vector<std::vector<T, A>> : std::true_type {};
template <class T> struct is_optional : std::false_type {};
template <class T> struct is_optional<std::optional<T>> : std::true_type {};
template <class T> struct is_variant : std::false_type {};
template <class... T> struct is_variant<std::variant<T...>> : std::true_type {};
template <class T> struct is_array : std::false_type {};
template <class T, std::size_t N> struct is_array<std::array<T, N>> : std::true_type {};

[[noreturn]] void bad_state(const char* what) {
    throw py::value_error(std::string("stickslip: cannot unpickle: ") + what);
}

template <class T> py::object encode(T& x);
template <class T> void decode(const py::handle& h, T& x);

/// Appends each member's state.
struct Save {
    py::list out;
    template <class... T> void operator()(T&... xs) { (out.append(encode(xs)), ...); }
};

/// Reads each member's state, in the order Save wrote them.
struct Load {
    py::tuple in;
    std::size_t next = 0;
    template <class... T> void operator()(T&... xs) {
        auto one = [this](auto& x) {
            if (next >= in.size()) bad_state("too few members (a pickle of another version?)");
            decode(in[next++], x);
        };
        (one(xs), ...);
    }
};

template <class T> concept HasFields = requires(Save& s, T& t) { fields(s, t); };

template <class T> py::object encode(T& x) {
    using U = std::remove_cv_t<T>;
    if constexpr (std::is_same_v<U, bool>) return py::bool_(x);
    else if constexpr (std::is_floating_point_v<U>) return py::float_(x);
    else if constexpr (std::is_integral_v<U>) return py::int_(x);
    else if constexpr (std::is_enum_v<U>) return py::int_(static_cast<std::underlying_type_t<U>>(x));
    else if constexpr (std::is_same_v<U, std::string>) return py::bytes(x); // any bytes, as they are
    // Columns of numbers as NumPy arrays: a path of a million points pickles in
    // milliseconds, and the array's dtype records its byte order.
    else if constexpr (std::is_same_v<U, std::vector<double>> || std::is_same_v<U, std::vector<int>>)
        return to_array(x);
    else if constexpr (is_vector<U>::value || is_array<U>::value) {
        py::list l;
        for (auto& e : x) l.append(encode(e));
        return l;
    } else if constexpr (is_optional<U>::value) return x ? encode(*x) : py::object(py::none());
    else if constexpr (is_variant<U>::value)
        return py::make_tuple(x.index(), std::visit([](auto& a) { return encode(a); }, x));
    else if constexpr (std::is_same_v<U, ExactBivariateSums>) {
        std::vector<std::uint64_t> w(ExactBivariateSums::words);
        x.to_words(w.data());
        return encode(w);
    } else if constexpr (std::is_same_v<U, ControlVariateSums>) {
        std::vector<std::uint64_t> w(x.words());
        x.to_words(w.data());
        return encode(w);
    } else if constexpr (std::is_same_v<U, BivariateMoments>) {
        std::vector<double> raw(BivariateMoments::raw_size);
        x.to_raw(raw.data());
        return encode(raw);
    }
    // the settings' views of their members (setting.hpp)
    else if constexpr (std::is_same_v<U, TextValue> || std::is_same_v<U, SeedValue> ||
                       std::is_same_v<U, OptionalNumber>)
        return encode(x.value);
    else if constexpr (std::is_same_v<U, NumberList>) return encode(x.values);
    else if constexpr (std::is_same_v<U, NumberOrAuto>) return py::make_tuple(encode(x.value), encode(x.automatic));
    else if constexpr (std::is_same_v<U, NumberRange>) return py::make_tuple(encode(x.lo), encode(x.hi));
    else {
        static_assert(HasFields<U>, "a member type with no fields() and no rule above");
        Save s;
        fields(s, x);
        return py::tuple(s.out);
    }
}

template <class V, std::size_t... I>
void decode_variant(std::size_t index, const py::handle& h, V& v, std::index_sequence<I...>) {
    if (index >= sizeof...(I)) bad_state("unknown alternative");
    ((index == I ? decode(h, v.template emplace<I>()) : void()), ...);
}

py::tuple as_tuple(const py::handle& h, std::size_t size) {
    if (!py::isinstance<py::tuple>(h)) bad_state("a tuple expected");
    auto t = py::reinterpret_borrow<py::tuple>(h);
    if (size && t.size() != size) bad_state("a tuple of another size");
    return t;
}

template <class T> void decode(const py::handle& h, T& x) {
    using U = std::remove_cv_t<T>;
    if constexpr (std::is_same_v<U, bool> || std::is_arithmetic_v<U> || std::is_same_v<U, std::string>) x = h.cast<U>();
    else if constexpr (std::is_enum_v<U>) x = static_cast<U>(h.cast<std::underlying_type_t<U>>());
    else if constexpr (std::is_same_v<U, std::vector<double>> || std::is_same_v<U, std::vector<int>>) {
        using Item = std::conditional_t<std::is_same_v<U, std::vector<double>>, double, std::int64_t>;
        if (!py::isinstance<py::array>(h)) bad_state("an array expected");
        const auto a = py::array_t<Item, py::array::c_style | py::array::forcecast>::ensure(h);
        if (!a || a.ndim() != 1) bad_state("a 1-D array expected");
        x.resize(static_cast<std::size_t>(a.size()));
        for (std::size_t k = 0; k < x.size(); ++k) x[k] = static_cast<typename U::value_type>(a.data()[k]);
    } else if constexpr (is_vector<U>::value) {
        if (!py::isinstance<py::list>(h)) bad_state("a list expected");
        auto l = py::reinterpret_borrow<py::list>(h);
        x.clear();
        x.resize(l.size());
        for (std::size_t k = 0; k < l.size(); ++k) decode(l[k], x[k]);
    } else if constexpr (is_array<U>::value) {
        auto l = py::reinterpret_borrow<py::list>(h);
        if (!py::isinstance<py::list>(h) || l.size() != x.size()) bad_state("a list of another size");
        for (std::size_t k = 0; k < x.size(); ++k) decode(l[k], x[k]);
    } else if constexpr (is_optional<U>::value) {
        if (h.is_none()) x.reset();
        else decode(h, x.emplace());
    } else if constexpr (is_variant<U>::value) {
        const py::tuple t = as_tuple(h, 2);
        decode_variant(t[0].cast<std::size_t>(), t[1], x, std::make_index_sequence<std::variant_size_v<U>>{});
    } else if constexpr (std::is_same_v<U, ExactBivariateSums>) {
        std::vector<std::uint64_t> w;
        decode(h, w);
        if (w.size() != ExactBivariateSums::words) bad_state("sums of another size");
        x = ExactBivariateSums::from_words(w.data());
    } else if constexpr (std::is_same_v<U, ControlVariateSums>) {
        std::vector<std::uint64_t> w;
        decode(h, w);
        if (w.size() != x.words()) bad_state("sums of another size");
        x.assign_words(w.data());
    } else if constexpr (std::is_same_v<U, BivariateMoments>) {
        std::vector<double> raw;
        decode(h, raw);
        if (raw.size() != static_cast<std::size_t>(BivariateMoments::raw_size)) bad_state("moments of another size");
        x = BivariateMoments::from_raw(raw.data());
    } else if constexpr (std::is_same_v<U, TextValue> || std::is_same_v<U, SeedValue> ||
                         std::is_same_v<U, OptionalNumber>)
        decode(h, x.value);
    else if constexpr (std::is_same_v<U, NumberList>) decode(h, x.values);
    else if constexpr (std::is_same_v<U, NumberOrAuto>) {
        const py::tuple t = as_tuple(h, 2);
        decode(t[0], x.value);
        decode(t[1], x.automatic);
    } else if constexpr (std::is_same_v<U, NumberRange>) {
        const py::tuple t = as_tuple(h, 2);
        decode(t[0], x.lo);
        decode(t[1], x.hi);
    } else {
        Load l{as_tuple(h, 0)};
        fields(l, x);
        if (l.next != l.in.size()) bad_state("too many members (a pickle of another version?)");
    }
}

/// The module's version, which a state is written with and read by.
constexpr const char* state_version = STICKSLIP_VERSION_STRING;

/// Adds __getstate__/__setstate__ to the bound class `name` of `m`.
template <class T>
void pickled(py::module_& m, const char* name) {
    auto cls = py::reinterpret_borrow<py::class_<T>>(m.attr(name));
    cls.def(py::pickle(
        [](const T& x) {
            // fields() takes its struct by reference, for Load; Save only reads it
            // (no copy of a result's paths).
            return py::make_tuple(state_version, encode(const_cast<T&>(x)));
        },
        [](const py::tuple& t) {
            if (t.size() != 2) bad_state("not a stickslip state");
            const auto version = t[0].cast<std::string>();
            if (version != state_version)
                bad_state(("it was written by stickslip " + version + ", this is " + state_version +
                           " (pickles are not portable across versions)")
                              .c_str());
            T x{};
            decode(t[1], x);
            return x;
        }));
}

} // namespace

void bind_pickling(py::module_& m) {
    // The parts of results, and the parameters.
    pickled<ModelParams>(m, "Params");
    pickled<Scales>(m, "Scales");
    pickled<Estimate>(m, "Estimate");
    pickled<EstimateSeries>(m, "EstimateSeries");
    pickled<VelocityHistogram>(m, "Histogram");
    pickled<SamplePath>(m, "Path");
    pickled<SweepExponent>(m, "SweepExponent");
    pickled<SweepWhiteLimit>(m, "SweepWhiteLimit");
    // The results.
    pickled<DiffusivityResult>(m, "DiffusivityResult");
    pickled<BruteForceResult>(m, "BruteForceResult");
    pickled<DensityResult>(m, "DensityResult");
    pickled<CorrelationResult>(m, "CorrelationResult");
    pickled<MomentsResult>(m, "MomentsResult");
    pickled<TrajectoryResult>(m, "TrajectoryResult");
    pickled<SweepResult>(m, "SweepResult");
    pickled<WhiteNoiseResult>(m, "WhiteNoiseResult");
    pickled<SpectrumResult>(m, "SpectrumResult");
    // The requests (a request sent to a worker process).
    pickled<DiffusivityRequest>(m, "DiffusivityRequest");
    pickled<BruteForceRequest>(m, "BruteForceRequest");
    pickled<DensityRequest>(m, "DensityRequest");
    pickled<CorrelationRequest>(m, "CorrelationRequest");
    pickled<MomentsRequest>(m, "MomentsRequest");
    pickled<TrajectoryRequest>(m, "TrajectoryRequest");
    pickled<SweepRequest>(m, "SweepRequest");
    pickled<WhiteNoiseRequest>(m, "WhiteNoiseRequest");
    pickled<SpectrumRequest>(m, "SpectrumRequest");
}

} // namespace stickslip::python
