// SPDX-License-Identifier: BSD-3-Clause
// The library's request structures, bound as they are, and the one entry
// point that runs any of them.
//
// A request is built from its C++ defaults; the Python functions set only the
// keywords they are given, through set(name, value), which writes the value
// as text and reads it with the library's own parser (setting.hpp): every
// default, range check and error message is the library's, exactly as on the
// command line. settings() describes every setting (name, unit, help,
// default), from which the Python layer writes each function's signature and
// docstring.
//
// Running: the computation runs on a helper thread with the GIL released,
// while the calling thread wakes every 50 ms to run Python's signal handlers.
// When a handler raises (KeyboardInterrupt), the run's stop flag is set: the
// workers start no new block and finish those in flight, the run returns the
// result of the blocks completed, and the exception is re-raised carrying it
// as its `result` attribute (None when there was nothing to report). A second
// exception while it stops cancels it within one sample. The library reports
// progress through RunControl::progress on whichever worker merged a block;
// with progress=True the waiting thread prints it on sys.stderr. Runs through
// the block driver take checkpoint=, checkpoint_every= and resume=
// (checkpoint.hpp), exactly as the command line's --checkpoint flags.
#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <chrono>
#include <cmath>
#include <functional>
#include <future>
#include <mutex>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>

#include "bindings.hpp"
#include "stickslip/bruteforce.hpp"
#include "stickslip/checkpoint.hpp"
#include "stickslip/detail/atomic_file.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/number_text.hpp"
#include "stickslip/observables.hpp"
#include "stickslip/report.hpp"
#include "stickslip/spectrum.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/white_noise.hpp"

namespace stickslip::python {

namespace {

/// An optional file name (None: not given).
using Path = std::optional<std::string>;

// ---- the settings as Python values ---------------------------------------------------

/// A setting's value as a Python object (the defaults of the signatures):
/// None for the settings whose default depends on others or is a list.
template <class Field>
py::object python_value(const Field& f) {
    using T = std::decay_t<Field>;
    if constexpr (std::is_same_v<T, bool>) return py::bool_(f);
    else if constexpr (std::is_same_v<T, double>) return py::float_(f);
    else if constexpr (std::is_integral_v<T>) return py::int_(f);
    else if constexpr (std::is_same_v<T, SeedValue>) return py::int_(f.value);
    else if constexpr (std::is_same_v<T, NumberOrAuto>)
        return f.automatic ? py::object(py::str("auto")) : py::object(py::float_(f.value));
    else if constexpr (std::is_enum_v<T>) return py::str(format_setting(f));
    else if constexpr (std::is_same_v<T, TextValue>) return py::str(f.value);
    else return py::none(); // OptionalNumber, NumberList, NumberRange
}

/// The Python type of a setting, as its docstring names it.
template <class Field>
const char* python_type(const Field&) {
    using T = std::decay_t<Field>;
    if constexpr (std::is_same_v<T, bool>) return "bool";
    else if constexpr (std::is_same_v<T, double>) return "float";
    else if constexpr (std::is_integral_v<T> || std::is_same_v<T, SeedValue>) return "int";
    else if constexpr (std::is_enum_v<T> || std::is_same_v<T, TextValue>) return "str";
    else if constexpr (std::is_same_v<T, OptionalNumber>) return "float or None";
    else if constexpr (std::is_same_v<T, NumberOrAuto>) return "float or 'auto'";
    else if constexpr (std::is_same_v<T, NumberList>) return "sequence of float or None";
    else return "(float, float) or None"; // NumberRange
}

/// Is `field` a member of the request's model parameters? Those come from the
/// `params` argument, not from keywords.
template <class Request, class Field>
bool in_params(const Request& r, const Field& field) {
    const auto* lo = reinterpret_cast<const char*>(&r.params);
    auto inside = [&](const void* member) {
        const auto* p = static_cast<const char*>(member);
        return p >= lo && p < lo + sizeof(ModelParams);
    };
    // The model's numbers, and its drift-law settings (a TextValue or an
    // OptionalNumber refers to the member; knots is an int member): all come
    // from `params`.
    if constexpr (std::is_same_v<Field, double> || std::is_same_v<Field, int>) return inside(&field);
    else if constexpr (std::is_same_v<Field, TextValue> || std::is_same_v<Field, OptionalNumber>)
        return inside(&field.value); // the drift law's texts, the static friction
    return false;
}

std::string keyword_of(const char* name) {
    std::string k = name;
    for (char& c : k)
        if (c == '-') c = '_';
    return k;
}

/// The keyword settings of a request, in order: (keyword, flag, unit, help,
/// default value, default text, form).
template <class Request>
py::list describe() {
    Request r;
    py::list out;
    visit_settings(r, [&](auto&& field, const SettingInfo& info) {
        if (in_params(r, field)) return;
        py::dict d;
        d["keyword"] = keyword_of(info.name);
        d["flag"] = std::string("--") + info.name;
        d["unit"] = info.unit;
        d["help"] = info.help;
        d["default"] = python_value(field);
        d["default_text"] = format_setting(field);
        d["form"] = info.form ? info.form : setting_form(field);
        d["type"] = python_type(field);
        out.append(d);
    });
    return out;
}

/// request.set(keyword, value): the value read by the library's parser; None
/// restores the default.
template <class Request>
void set_setting(Request& r, const std::string& keyword, const py::object& value) {
    Request defaults;
    bool found = false;
    std::string default_text;
    std::size_t k = 0, index = 0;
    visit_settings(defaults, [&](auto&& field, const SettingInfo& info) {
        if (!in_params(defaults, field) && keyword_of(info.name) == keyword) {
            found = true;
            index = k;
            default_text = format_setting(field);
        }
        ++k;
    });
    if (!found) throw py::type_error("unexpected keyword argument '" + keyword + "'");
    const std::string text = value.is_none() ? default_text : setting_text(value);
    k = 0;
    visit_settings(r, [&](auto&& field, const SettingInfo& info) {
        if (k++ == index) parse_setting(info, text, field);
    });
}

/// request.get(keyword): the value as a Python object (lists as lists, unset
/// optional numbers as None).
template <class Request>
py::object get_setting(Request& r, const std::string& keyword) {
    py::object out;
    bool found = false;
    visit_settings(r, [&](auto&& field, const SettingInfo& info) {
        if (found || in_params(r, field) || keyword_of(info.name) != keyword) return;
        found = true;
        using T = std::decay_t<decltype(field)>;
        if constexpr (std::is_same_v<T, NumberList>) out = py::cast(field.values);
        else if constexpr (std::is_same_v<T, NumberRange>)
            out = field.lo == 0 && field.hi == 0 ? py::object(py::none()) : py::object(py::make_tuple(field.lo, field.hi));
        else if constexpr (std::is_same_v<T, OptionalNumber>)
            out = std::isnan(field.value) ? py::object(py::none()) : py::object(py::float_(field.value));
        else out = python_value(field);
    });
    if (!found) throw py::attribute_error("no setting '" + keyword + "'");
    return out;
}

// ---- running --------------------------------------------------------------------------

/// Shared between the computation (progress callbacks, any thread) and the
/// waiting Python thread.
struct Monitor {
    std::atomic<bool> stop{false};   ///< the first Ctrl-C: finish the blocks in flight
    std::atomic<bool> cancel{false}; ///< the second: stop within one sample
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

    /// Whether a line without its newline is on sys.stderr.
    bool open_line = false;

    /// Ends the progress line, if one is open (needs the GIL): whatever
    /// follows, a traceback or the next output, starts on a line of its own.
    void end_line() {
        if (!open_line) return;
        open_line = false;
        try {
            py::object err = py::module_::import("sys").attr("stderr");
            if (err.is_none()) return;
            err.attr("write")("\n");
            err.attr("flush")();
        } catch (py::error_already_set&) {
        }
    }

    /// One progress line on sys.stderr (needs the GIL); `final` ends it with
    /// a newline. Errors are ignored.
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
        std::string line = "\r"; // appended: GCC 12 warns (-Wrestrict, a false positive) on "\r" + std::string
        // Before anything is done the time left is unknown, not "~0 s" (as the CLI's line).
        line += std::to_string(d) + "/" + std::to_string(t) + " " + what + ", " + number_text::fixed(s, 1) +
                " s elapsed, " + (rate > 0 || d == t ? "~" + number_text::fixed(left, 0) + " s left   " : "estimating...   ") +
                (final ? "\n" : "");
        try {
            py::object err = py::module_::import("sys").attr("stderr");
            if (err.is_none()) return;
            err.attr("write")(line);
            err.attr("flush")();
            open_line = !final;
        } catch (py::error_already_set&) {
        }
    }
};

/// Runs work() on a helper thread with the GIL released; Ctrl-C (any Python
/// exception raised by a signal handler) stops it through `mon` (a second one
/// cancels it) and is re-raised, with the result so far, if any, as its
/// `result` attribute. Called with the GIL held.
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
            if (PyErr_CheckSignals() != 0) {
                if (!interrupted) {
                    interrupted.emplace(); // fetches (and clears) the pending exception
                    mon.stop = true;
                } else {
                    PyErr_Clear(); // the first one is re-raised
                    mon.cancel = true;
                }
            }
            const auto now = std::chrono::steady_clock::now();
            if (show_progress && !interrupted && now - last_print >= std::chrono::milliseconds(500)) {
                last_print = now;
                mon.print(false);
            }
        }
    }
    // Whatever ends the run (a result, Ctrl-C, an error), a progress line
    // printed is ended with a newline.
    if (interrupted) mon.end_line();
    auto raise_with = [&](py::object result) {
        try {
            py::setattr(interrupted->value(), "result", std::move(result));
        } catch (py::error_already_set&) { // an exception type without attributes: raise it as it is
        }
        throw *interrupted;
    };
    try {
        try {
            Result r = fut.get();
            if (interrupted) raise_with(py::cast(r)); // the prefix of the run (or all of it, if it ended first)
            if (show_progress) mon.print(true);
            return r;
        } catch (const RunCancelled&) {
            if (interrupted) raise_with(py::none());
            throw;
        } catch (const RunInterrupted&) {
            if (interrupted) raise_with(py::none());
            throw;
        }
    } catch (...) {
        mon.end_line(); // an error: its traceback starts on a line of its own
        throw;
    }
}

/// The journal of a run from its checkpoint keywords (None: not asked for).
template <class Request>
std::unique_ptr<RunJournal> journal_for(Request& req, const std::optional<std::string>& checkpoint,
                                        double checkpoint_every, const std::optional<std::string>& resume) {
    CheckpointOptions o;
    o.path = checkpoint.value_or("");
    o.every = checkpoint_every;
    o.resume = resume.value_or("");
    return make_journal(req, o);
}

/// Runs a request that goes through the block driver: Ctrl-C keeps the result
/// so far, and the journal (if any) is written at the end or when stopped.
template <class Request, class Result>
Result run_journaled(Request& req, std::function<Result()> compute, Monitor& mon, bool progress,
                     RunJournal* journal) {
    req.control.stop = &mon.stop;
    req.control.journal = journal;
    try {
        Result r = run_interruptible<Result>(std::move(compute), mon, progress);
        if (journal) journal->write();
        return r;
    } catch (const py::error_already_set&) {
        if (journal) journal->write(); // KeyboardInterrupt: the state so far
        throw;
    }
}

/// What the progress line counts for each request.
const char* samples_of(const DiffusivityRequest&) { return "excursions"; }
const char* samples_of(const BruteForceRequest&) { return "trajectories"; }
const char* samples_of(const DensityRequest&) { return "excursions"; }
const char* samples_of(const CorrelationRequest&) { return "excursions"; }
const char* samples_of(const MomentsRequest&) { return "trajectories"; }
const char* samples_of(const TrajectoryRequest&) { return "paths"; }
const char* samples_of(const SpectrumRequest&) { return "excursions"; } // Monte Carlo; a solve reports none

/// Forgets what points into a run's monitor and journal, about to go.
template <class Result>
void detach(Result& r) {
    r.request.control.progress = nullptr;
    r.request.control.cancel = nullptr;
    r.request.control.stop = nullptr;
    r.request.control.journal = nullptr;
}

/// The CLI's last check, before a result is returned: a number its JSON would
/// print as null (NaN, inf) makes it untrustworthy (the command's exit 3;
/// Python returned NaN, inf or a negative D silently, issue 50). The result
/// goes with the exception, as e.result.
template <class Result>
Result checked(Result r) {
    try {
        check_finite_result(to_json(r));
    } catch (const UntrustworthyResult& e) {
        detach(r);
        raise_untrustworthy(e.what(), py::cast(r));
    }
    return r;
}

template <class Request, class Result>
Result run_request(Request req, Result (*compute)(const Request&), bool progress) {
    Monitor mon;
    req.control.progress_interval = 0.0; // check the cancel flag after every merged block
    req.control.progress = mon.callback(samples_of(req));
    req.control.cancel = &mon.cancel; // stops the workers within one sample
    Result r = run_interruptible<Result>([&req, compute] { return compute(req); }, mon, progress);
    detach(r);
    return checked(std::move(r));
}

template <class Request, class Result>
Result run_resumable(Request req, Result (*compute)(const Request&), bool progress,
                     const std::optional<std::string>& checkpoint, double checkpoint_every,
                     const std::optional<std::string>& resume) {
    Monitor mon;
    req.control.progress_interval = 0.0; // check the cancel flag after every merged block
    req.control.progress = mon.callback(samples_of(req));
    req.control.cancel = &mon.cancel;
    const auto journal = journal_for(req, checkpoint, checkpoint_every, resume);
    Result r = run_journaled<Request, Result>(req, [&req, compute] { return compute(req); }, mon, progress,
                                              journal.get());
    detach(r);
    return checked(std::move(r));
}

SweepResult run_sweep(SweepRequest req, bool progress, const std::optional<std::string>& checkpoint,
                      double checkpoint_every, const std::optional<std::string>& resume) {
    Monitor mon;
    req.control.progress_interval = 0.0;
    req.point_progress = [&mon](std::size_t k, std::size_t n, const std::string& point) {
        return mon.callback("excursions (point " + std::to_string(k + 1) + "/" + std::to_string(n) + ": " + point +
                            ")");
    };
    // A solved sweep (engine='kolmogorov') counts points, and checks for
    // Ctrl-C between them (SweepRequest).
    if (!samples(req.engine)) req.control.progress = mon.callback("points solved (kolmogorov engine)");
    req.control.cancel = &mon.cancel; // every point's run stops within one sample
    const auto journal = journal_for(req, checkpoint, checkpoint_every, resume);
    SweepResult r = run_journaled<SweepRequest, SweepResult>(req, [&req] { return compute_sweep(req); }, mon,
                                                             progress, journal.get());
    r.request.point_progress = nullptr; // it points to `mon`, about to go
    detach(r);
    return checked(std::move(r));
}

/// Binds one request type: construction from the defaults, set/get, the
/// model parameters, validate(), the settings' descriptions.
template <class Request>
void bind_request(py::module_& m, const char* name, const char* doc) {
    py::class_<Request> cls(m, name, doc);
    // Whether run() takes checkpoint=, checkpoint_every= and resume= for it.
    if constexpr (requires { Request::resumable; }) cls.attr("resumable") = py::bool_(Request::resumable);
    else cls.attr("resumable") = py::bool_(false);
    cls
        .def(py::init<>(), "A request with every setting at its default (the CLI's).")
        .def("set", &set_setting<Request>, py::arg("keyword"), py::arg("value"),
             "Set one setting from a Python value (number, bool, str, sequence; None restores the default), read "
             "by the library's parser: bad values raise InvalidParameterError with the CLI's message.")
        .def("get", &get_setting<Request>, py::arg("keyword"), "The current value of one setting.")
        .def_property(
            "params", [](const Request& r) { return r.params; },
            [](Request& r, const ModelParams& p) { r.params = p; }, "The model parameters (Params).")
        .def_property(
            "command", [](const Request& r) { return r.command_line; },
            [](Request& r, std::string c) { r.command_line = std::move(c); },
            "What asks for the run, as the result's JSON (\"command\") and CSV ('# command:') record it: the "
            "keyword functions set their call; '' (the default) records null.")
        .def("validate", [](const Request& r) { validate(r); },
             "Check the request as a run would (InvalidParameterError on the first problem).")
        .def_static("settings", &describe<Request>,
                    "The keyword settings, in order: dicts with 'keyword', 'flag', 'unit', 'help', 'default', "
                    "'default_text', 'form'.");
}

/// Adds every setting of `Request` to the flag -> keyword table.
template <class Request>
void add_keywords(std::vector<std::pair<std::string, std::string>>& table) {
    Request r;
    visit_settings(r, [&](auto&&, const SettingInfo& info) {
        const std::string flag = std::string("--") + info.name;
        for (const auto& [f, k] : table)
            if (f == flag) return;
        table.emplace_back(flag, keyword_of(info.name));
    });
}

} // namespace

const std::vector<std::pair<std::string, std::string>>& keyword_table() {
    static const auto table = [] {
        std::vector<std::pair<std::string, std::string>> t;
        add_keywords<DiffusivityRequest>(t);
        add_keywords<BruteForceRequest>(t);
        add_keywords<DensityRequest>(t);
        add_keywords<CorrelationRequest>(t);
        add_keywords<MomentsRequest>(t);
        add_keywords<TrajectoryRequest>(t);
        add_keywords<SweepRequest>(t);
        add_keywords<WhiteNoiseRequest>(t);
        add_keywords<SpectrumRequest>(t);
        for (const char* flag : {"checkpoint", "checkpoint-every", "resume"})
            t.emplace_back(std::string("--") + flag, keyword_of(flag));
        return t;
    }();
    return table;
}

std::string python_text(const std::string& note) {
    // Every "--name" that is a flag of a setting, whole (not the start of a
    // longer flag), becomes its keyword; anything else is left as it is.
    const auto& table = keyword_table();
    std::string out;
    std::size_t k = 0;
    while (k < note.size()) {
        if (note.compare(k, 2, "--") == 0 && (k == 0 || note[k - 1] != '-')) {
            std::size_t end = k + 2;
            while (end < note.size() && (std::isalnum(static_cast<unsigned char>(note[end])) || note[end] == '-'))
                ++end;
            const std::string flag = note.substr(k, end - k);
            const auto it = std::find_if(table.begin(), table.end(), [&](const auto& e) { return e.first == flag; });
            if (it != table.end()) {
                out += it->second;
                k = end;
                continue;
            }
        }
        out += note[k++];
    }
    return out;
}

void write_output_file(const std::string& path, std::string_view bytes) {
    const detail::FileTarget t = detail::resolve_target(path);
    if (t.error != 0 || t.kind == detail::FileTarget::Kind::directory)
        throw py::value_error("cannot write '" + path + "': " +
                              std::strerror(t.error != 0 ? t.error : EISDIR));
    if (t.kind == detail::FileTarget::Kind::missing || t.kind == detail::FileTarget::Kind::regular) {
        py::gil_scoped_release nogil;
        detail::write_file_atomically(t.path, bytes); // a temporary renamed into place, as --output
        return;
    }
    py::object f = py::module_::import("builtins").attr("open")(path, "wb"); // a device, FIFO: written through
    f.attr("write")(py::bytes(bytes.data(), bytes.size()));
    f.attr("close")();
}

void bind_requests(py::module_& m) {
    {
        py::dict table;
        for (const auto& [flag, keyword] : keyword_table()) table[py::str(flag)] = keyword;
        m.attr("keyword_of_flag") = table; // the CLI's flag -> the Python keyword, generated from the settings
    }
    m.def("python_text", &python_text, py::arg("note"),
          "A note of the library with every setting's flag written as its Python keyword (keyword_of_flag).");
    m.def(
        "write_output_file",
        [](const std::string& path, py::bytes data) { write_output_file(path, std::string(data)); },
        py::arg("path"), py::arg("data"),
        "Write bytes to path as the CLI's --output does: a regular or new file atomically (a temporary in its "
        "folder renamed into place: nothing left behind on failure), a device or FIFO directly.");
    py::dict checkpoint_help;
    checkpoint_help["checkpoint"] = CheckpointOptions::path_help;
    checkpoint_help["checkpoint_every"] = CheckpointOptions::every_help;
    checkpoint_help["resume"] = CheckpointOptions::resume_help;
    m.attr("checkpoint_help") = checkpoint_help; // the keywords' help texts, as the CLI's flags have them
    m.attr("checkpoint_every_default") = CheckpointOptions{}.every;

    bind_request<DiffusivityRequest>(m, "DiffusivityRequest", "The settings of a diffusivity run.");
    bind_request<BruteForceRequest>(m, "BruteForceRequest", "The settings of a brute-force run.");
    bind_request<DensityRequest>(m, "DensityRequest", "The settings of a stationary density run.");
    bind_request<CorrelationRequest>(m, "CorrelationRequest", "The settings of an autocorrelation run.");
    bind_request<MomentsRequest>(m, "MomentsRequest", "The settings of a transient moments run.");
    bind_request<TrajectoryRequest>(m, "TrajectoryRequest", "The settings of a sample-path run.");
    bind_request<SweepRequest>(m, "SweepRequest", "The settings of a sweep over noise and tau.");
    bind_request<WhiteNoiseRequest>(m, "WhiteNoiseRequest", "The settings of the exact white-noise references.");
    bind_request<SpectrumRequest>(m, "SpectrumRequest", "The settings of a velocity spectrum.");

    const char* run_doc =
        "Run a request and return its result. The GIL is released; progress=True prints a progress line on "
        "sys.stderr. Ctrl-C lets the blocks in flight finish and raises KeyboardInterrupt whose `result` attribute "
        "is the result so far (marked interrupted), or None. checkpoint=FILE saves the run's state every "
        "checkpoint_every seconds and at the end; resume=FILE continues it (runs over excursions or trajectories).";
    m.def(
         "run",
            [](const DiffusivityRequest& r, bool p, const Path& c, double e, const Path& res) {
                return run_resumable(r, &compute_diffusivity, p, c, e, res);
            },
            py::arg("request"), py::arg("progress") = false, py::arg("checkpoint") = py::none(),
            py::arg("checkpoint_every") = CheckpointOptions{}.every, py::arg("resume") = py::none(), run_doc)
        .def(
            "run",
            [](const BruteForceRequest& r, bool p, const Path& c, double e, const Path& res) {
                return run_resumable(r, &compute_bruteforce, p, c, e, res);
            },
            py::arg("request"), py::arg("progress") = false, py::arg("checkpoint") = py::none(),
            py::arg("checkpoint_every") = CheckpointOptions{}.every, py::arg("resume") = py::none())
        .def(
            "run",
            [](const DensityRequest& r, bool p, const Path& c, double e, const Path& res) {
                return run_resumable(r, &compute_density, p, c, e, res);
            },
            py::arg("request"), py::arg("progress") = false, py::arg("checkpoint") = py::none(),
            py::arg("checkpoint_every") = CheckpointOptions{}.every, py::arg("resume") = py::none())
        .def(
            "run",
            [](const CorrelationRequest& r, bool p, const Path& c, double e, const Path& res) {
                return run_resumable(r, &compute_correlation, p, c, e, res);
            },
            py::arg("request"), py::arg("progress") = false, py::arg("checkpoint") = py::none(),
            py::arg("checkpoint_every") = CheckpointOptions{}.every, py::arg("resume") = py::none())
        .def(
            "run",
            [](const MomentsRequest& r, bool p, const Path& c, double e, const Path& res) {
                return run_resumable(r, &compute_moments, p, c, e, res);
            },
            py::arg("request"), py::arg("progress") = false, py::arg("checkpoint") = py::none(),
            py::arg("checkpoint_every") = CheckpointOptions{}.every, py::arg("resume") = py::none())
        .def(
            "run", [](const TrajectoryRequest& r, bool p) { return run_request(r, &compute_trajectory, p); },
            py::arg("request"), py::arg("progress") = false)
        .def(
            "run",
            [](const SweepRequest& r, bool p, const Path& c, double e, const Path& res) {
                return run_sweep(r, p, c, e, res);
            },
            py::arg("request"), py::arg("progress") = false, py::arg("checkpoint") = py::none(),
            py::arg("checkpoint_every") = CheckpointOptions{}.every, py::arg("resume") = py::none())
        .def(
            "run",
            [](const SpectrumRequest& r, bool p, const Path& c, double e, const Path& res) {
                return run_resumable(r, &compute_spectrum, p, c, e, res);
            },
            py::arg("request"), py::arg("progress") = false, py::arg("checkpoint") = py::none(),
            py::arg("checkpoint_every") = CheckpointOptions{}.every, py::arg("resume") = py::none())
        .def(
            "run",
            [](const WhiteNoiseRequest& r, bool) {
                py::gil_scoped_release nogil; // quadratures and closed forms: quick, nothing to interrupt
                return compute_white_noise(r);
            },
            py::arg("request"), py::arg("progress") = false);

    m.def(
        "spaced_values",
        [](double lo, double hi, std::uint64_t n, bool linear) { return spaced_values(lo, hi, n, linear); },
        py::arg("lo"), py::arg("hi"), py::arg("n"), py::arg("linear") = false,
        "n values from lo to hi, log-spaced (or evenly, linear=True), endpoints exact: what lo:hi:n means.");
}

} // namespace stickslip::python
