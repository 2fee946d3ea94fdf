// SPDX-License-Identifier: BSD-3-Clause
// A user's drift law made into knots (drift_input.hpp says how and why).
#include "stickslip/drift_input.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>

#include <muParser.h>

#include "core/format.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/setting.hpp"

namespace stickslip {
namespace {

using detail::format_number;

/// s without its leading and trailing blanks.
std::string trim(std::string s) {
    s.erase(0, s.find_first_not_of(" \t"));
    s.erase(s.find_last_not_of(" \t") + 1);
    return s;
}

[[noreturn]] void fail(const char* setting, const std::string& what) {
    throw InvalidParameter(setting, what); // the front ends name the setting
}

/// The expression as a function of v, parsed once by muParser; its named
/// constants from drift_params. muParser reports an unknown name as an
/// unexpected token, so the names are collected by a variable factory and
/// anything but v and the given constants is refused by name.
class Expression {
public:
    Expression(const std::string& text, const std::string& params) {
        refuse_statements(text);
        parse_params(params);
        try {
            parser_.DefineVar("v", &v_);
            for (auto& [name, value] : constants_) parser_.DefineVar(name, &value);
            parser_.SetVarFactory(&Expression::unknown, this);
            parser_.SetExpr(text);
            parser_.Eval(); // parses now, so that a syntax error is reported here
        } catch (const mu::Parser::exception_type& e) {
            fail("drift", "cannot read \"" + text + "\": " + e.GetMsg());
        }
        if (!unknown_.empty())
            fail("drift", "\"" + text + "\" names '" + unknown_.front() +
                              "'; the law is a function of v (m/s) alone; give other names a value with "
                              "--drift-params \"" + unknown_.front() + "=...\"");
    }
    double operator()(double v) {
        v_ = v;
        try {
            return parser_.Eval();
        } catch (const mu::Parser::exception_type& e) {
            fail("drift", "cannot evaluate at v = " + format_number(v) + " m/s: " + e.GetMsg());
        }
    }

private:
    /// muParser also reads an assignment ("v=3" sets v and yields 3) and a
    /// list ("-v,2*v" evaluates both and yields the last): neither is a law
    /// b(v), so an '=' outside <=, >=, ==, != and a ',' outside a function's
    /// parentheses are refused.
    static void refuse_statements(const std::string& text) {
        int depth = 0;
        for (std::size_t i = 0; i < text.size(); ++i) {
            const char c = text[i];
            if (c == '(') ++depth;
            else if (c == ')') --depth;
            else if (c == ',' && depth <= 0)
                fail("drift", "\"" + text + "\" is a list of expressions (a comma outside a function's "
                              "arguments); the law is one expression of v");
            else if (c == '=') {
                const char before = i > 0 ? text[i - 1] : ' ', after = i + 1 < text.size() ? text[i + 1] : ' ';
                const bool comparison = before == '<' || before == '>' || before == '=' || before == '!' || after == '=';
                if (!comparison)
                    fail("drift", "\"" + text + "\" assigns with '=': the law is an expression of v (compare with ==)");
            }
        }
    }
    static double* unknown(const char* name, void* self) {
        auto* e = static_cast<Expression*>(self);
        e->unknown_.emplace_back(name);
        e->spare_.push_back(std::make_unique<double>(0.0));
        return e->spare_.back().get();
    }
    void parse_params(const std::string& text) {
        std::stringstream in(text);
        std::string item;
        while (std::getline(in, item, ',')) {
            const auto eq = item.find('=');
            if (eq == std::string::npos) fail("drift-params", "each item must be NAME=NUM, got \"" + item + "\"");
            const std::string name = trim(item.substr(0, eq)), value = trim(item.substr(eq + 1));
            if (name.empty() || name == "v" || !std::isalpha(static_cast<unsigned char>(name[0])))
                fail("drift-params", "\"" + name + "\" is not a name for a constant (letters first; not v)");
            double x;
            parse_setting(SettingInfo{"drift-params", "", ""}, value, x);
            if (!std::isfinite(x)) fail("drift-params", name + " must be finite, got " + value);
            // The last of two values won before: which one was meant is unknowable.
            if (constants_.count(name))
                fail("drift-params", name + " is given twice (" + format_number(constants_[name]) + " and " + value +
                                         "); give each constant once");
            constants_[name] = x;
        }
    }
    mu::Parser parser_;
    double v_ = 0.0;
    std::map<std::string, double> constants_;
    std::vector<std::string> unknown_;
    std::vector<std::unique_ptr<double>> spare_;
};

/// muParser's variable factory for drift_expression_constants: a fresh
/// double for each name, kept in the vector passed as user data.
double* spare_variable(const char*, void* spares) {
    auto* v = static_cast<std::vector<std::unique_ptr<double>>*>(spares);
    v->push_back(std::make_unique<double>(0.0));
    return v->back().get();
}

/// The piecewise-linear interpolant of sorted rows, continued by the outer rows' lines.
struct TableLaw {
    std::vector<double> v, b;
    double operator()(double x) const {
        auto it = std::upper_bound(v.begin(), v.end(), x);
        std::size_t j = it == v.begin() ? 0 : static_cast<std::size_t>(it - v.begin()) - 1;
        j = std::min(j, v.size() - 2);
        return b[j] + (x - v[j]) * (b[j + 1] - b[j]) / (v[j + 1] - v[j]);
    }
};

void check_table(const std::vector<double>& v, const std::vector<double>& b, const char* setting) {
    if (v.size() != b.size()) fail(setting, "v and b have different lengths (" + std::to_string(v.size()) +
                                               " and " + std::to_string(b.size()) + ")");
    if (v.size() < 2) fail(setting, "needs at least two rows, got " + std::to_string(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (!std::isfinite(v[i]) || !std::isfinite(b[i]))
            fail(setting, "row " + std::to_string(i + 1) + " is not two finite numbers (v = " + format_number(v[i]) +
                              ", b = " + format_number(b[i]) + ")");
        if (i > 0 && !(v[i] > v[i - 1]))
            fail(setting, std::string(v[i] == v[i - 1] ? "duplicate" : "unsorted") + " v at row " +
                              std::to_string(i + 1) + " (" + format_number(v[i]) + " after " +
                              format_number(v[i - 1]) + "): rows must have strictly increasing v");
    }
}

/// How far the velocity reaches on one side (sign +1 or -1) [m/s]: see the
/// header. Throws when the law does not pull back within 1e5 velocity units.
double reach(const std::function<double(double)>& b, const ModelParams& p, int sign, const char* setting,
             const std::string& text) {
    const double unit = p.noise / p.friction, dv = unit / 32.0;
    constexpr long kMaxSteps = 32L * 100000L;
    double phi = 0.0, phi_max = 0.0, prev = b(0.0) - sign * p.friction, white_reach = -1.0;
    auto net = [&](double v) { // net deterministic force, checked finite
        const double g = b(v) - sign * p.friction;
        if (!std::isfinite(g)) fail(setting, "b(v) is not finite at v = " + format_number(v) + " m/s");
        return g;
    };
    for (long k = 1; k <= kMaxSteps && white_reach < 0; ++k) {
        const double v = sign * dv * static_cast<double>(k);
        const double g = net(v);
        phi += sign * 0.5 * (g + prev) * dv * 2.0 / p.noise;
        prev = g;
        phi_max = std::max(phi_max, phi);
        if (sign * g < 0 && phi < phi_max - 36.0) white_reach = std::fabs(v);
    }
    bool confined = white_reach > 0;
    // The law must keep pulling back beyond: checked at a few far points.
    for (double far : {2.0, 4.0, 16.0, 256.0, 65536.0})
        if (confined && !(sign * net(sign * far * white_reach) < 0)) confined = false;
    if (!confined)
        fail(setting, "the law " + text + " does not confine the velocity: a stationary state needs b(v) < friction (" +
                          format_number(p.friction) + " m s^-2) for all large v and b(v) > -friction for all " +
                          "large negative v; here b(v) " + (sign > 0 ? "- friction" : "+ friction") +
                          " does not keep the sign opposite to v's for large " + (sign > 0 ? "positive" : "negative") +
                          " v");
    double reach = white_reach;
    if (!p.white()) {
        // Coloured noise: a force of 9 standard deviations of a X, held for a
        // few tau, drives the velocity to its terminal value or by force*3 tau.
        const double force = p.force_amplitude() * 6.0 / std::sqrt(p.tau);
        double coloured = force * 3.0 * p.tau;
        for (long k = 1; static_cast<double>(k) * dv < std::min(coloured, 64.0 * white_reach); ++k)
            if (sign * net(sign * dv * static_cast<double>(k)) + force < 0) {
                coloured = dv * static_cast<double>(k);
                break;
            }
        reach = std::max(reach, coloured);
    }
    return 1.25 * reach + dv;
}

} // namespace

void read_drift_table(const std::string& path, std::vector<double>& v, std::vector<double>& b, std::string* digest) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        fail("drift-table", "'" + printable_text(path) + "' is a directory, not a file of v,b rows");
    std::ifstream file(path, std::ios::binary);
    if (!file) fail("drift-table", "cannot read '" + printable_text(path) + "'");
    // The whole file, bounded, in one pass (it may be a pipe, read once).
    std::string text;
    char chunk[1 << 16];
    while (file.read(chunk, sizeof chunk) || file.gcount() > 0) {
        text.append(chunk, static_cast<std::size_t>(file.gcount()));
        if (text.size() > drift_table_max_bytes)
            fail("drift-table", "'" + printable_text(path) + "' is larger than " +
                                    std::to_string(drift_table_max_bytes >> 20) +
                                    " MiB: not a table of v,b rows (at most " + std::to_string(drift_table_max_rows) +
                                    " rows are read)");
    }
    if (digest) {
        std::uint64_t h = 0xcbf29ce484222325ull; // FNV-1a
        for (unsigned char c : text) h = (h ^ c) * 0x100000001b3ull;
        char hex[17];
        std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
        *digest = std::string("fnv1a64:") + hex;
    }
    std::istringstream in(text);
    v.clear();
    b.clear();
    std::string line;
    int number = 0;
    bool header_seen = false;
    while (std::getline(in, line)) {
        ++number;
        if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        for (char& ch : line)
            if (ch == ',' || ch == ';' || ch == '\t' || ch == '\r') ch = ' ';
        std::istringstream row(line);
        std::string a, c, extra;
        row >> a >> c >> extra;
        double x = 0, y = 0;
        try {
            std::size_t ia = 0, ic = 0;
            // stod reads hexadecimal ("0x10" is 16): a table of numbers in
            // another base is a mistake, not a law.
            for (const std::string* cell : {&a, &c})
                if (cell->find_first_of("xXpP") != std::string::npos) throw std::invalid_argument("hex");
            x = std::stod(a, &ia);
            y = std::stod(c, &ic);
            if (ia != a.size() || ic != c.size() || !extra.empty()) throw std::invalid_argument("row");
        } catch (const std::exception&) {
            if (v.empty() && !header_seen) { // one header line of names
                header_seen = true;
                continue;
            }
            fail("drift-table", "'" + printable_text(path) + "' line " + std::to_string(number) +
                                    " is not two numbers v,b: \"" + printable_text(line) + "\"");
        }
        v.push_back(x);
        b.push_back(y);
        if (v.size() > drift_table_max_rows)
            fail("drift-table", "'" + printable_text(path) + "' has more than " + std::to_string(drift_table_max_rows) +
                                    " rows: the law is interpolated on at most " +
                                    std::to_string(DriftLaw::max_knots) + " knots; thin the table");
    }
}

void read_drift_inputs(ModelParams& p) {
    if (p.drift_table.empty() || !p.drift_table_v.empty()) return;
    read_drift_table(p.drift_table, p.drift_table_v, p.drift_table_b, &p.drift_table_digest);
}

namespace {

/// Makes the law of p (make_drift_law's work, without the memo).
DriftLaw build_drift_law(const ModelParams& p, DriftLawReport* report) {
    if (!p.has_drift_law()) {
        if (report) {
            *report = DriftLawReport{};
            report->source = "affine";
            report->text = "b = -v/relaxation + bias";
        }
        return affine_drift_law(p.relaxation, p.bias);
    }
    if (p.knots < 3 || p.knots > DriftLaw::max_knots || p.knots % 2 == 0)
        fail("knots", "must be odd, from 3 to " + std::to_string(DriftLaw::max_knots) + ", got " +
                          std::to_string(p.knots));
    std::function<double(double)> b;
    std::string source, text;
    const char* setting = "drift";
    if (!p.drift.empty()) {
        auto e = std::make_shared<Expression>(p.drift, p.drift_params);
        b = [e](double v) { return (*e)(v); };
        source = "expression";
        text = p.drift;
    } else if (!p.drift_table.empty() || !p.drift_table_v.empty()) {
        auto t = std::make_shared<TableLaw>();
        setting = "drift-table";
        if (!p.drift_table_v.empty()) { // the rows read once (read_drift_inputs), or given directly
            t->v = p.drift_table_v;
            t->b = p.drift_table_b;
            text = !p.drift_table.empty() ? p.drift_table : std::to_string(t->v.size()) + " rows given directly";
        } else {
            read_drift_table(p.drift_table, t->v, t->b);
            text = p.drift_table;
        }
        check_table(t->v, t->b, setting);
        b = [t](double v) { return (*t)(v); };
        source = "table";
    } else {
        b = p.drift_function;
        source = "function";
        text = "b(v)";
    }
    const double b0 = b(0.0);
    if (!std::isfinite(b0)) fail(setting, "b(0) is not finite");
    const double lo = reach(b, p, -1, setting, text), hi = reach(b, p, +1, setting, text);
    // Uniform knots with one at 0: m below it, n - 1 - m above.
    const int n = p.knots;
    int m = static_cast<int>(std::lround(static_cast<double>(n - 1) * lo / (lo + hi)));
    m = std::clamp(m, 1, n - 2);
    const double h = std::max(lo / m, hi / (n - 1 - m));
    DriftLaw law;
    law.kind = DriftLaw::Kind::Knots;
    law.knots = n;
    law.spacing = h;
    law.inv_spacing = 1.0 / h;
    law.first = -h * m;
    for (int k = 0; k < n; ++k) {
        const double v = k == m ? 0.0 : law.knot(k);
        law.values[k] = k == m ? b0 : b(v);
        if (!std::isfinite(law.values[k]))
            fail(setting, "b(v) is not finite at v = " + format_number(v) + " m/s");
    }
    double err = 0.0;
    for (int j = 0; j + 1 < n; ++j) {
        const double mid = law.knot(j) + 0.5 * h;
        const double bm = b(mid);
        if (!std::isfinite(bm)) fail(setting, "b(v) is not finite at v = " + format_number(mid) + " m/s");
        err = std::max(err, std::fabs(bm - law(mid)));
    }
    if (!confines(law, p.friction))
        fail(setting, "the law " + text + " does not confine the velocity beyond its knots");
    if (report) {
        *report = DriftLawReport{};
        report->source = source;
        report->text = text;
        report->interpolation_error = err;
        report->lower = law.knot(0);
        report->upper = law.knot(n - 1);
        report->knots = n;
        // Second order for a smooth law: halving the spacing quarters the error.
        const double target = 1e-3 * p.friction;
        if (err > target) {
            const double need = 1.0 + static_cast<double>(n - 1) * std::sqrt(err / target);
            report->notes.push_back(
                "the drift law's interpolant on " + std::to_string(n) + " knots is off by up to " +
                format_number(err, 3) + " m s^-2 (" + format_number(err / p.friction, 3) +
                " friction); about " + format_number(need, 2) + " knots would bring it below 1e-3 friction" +
                (need > DriftLaw::max_knots ? " (more than the " + std::to_string(DriftLaw::max_knots) +
                                                  " allowed: the law varies too fast for its velocity range)"
                                            : std::string(" (--knots)")));
        }
    }
    return law;
}

/// Everything of ModelParams that the made law can depend on, doubles by
/// their bits: equal inputs make the same law, bit for bit.
struct DriftLawInputs {
    std::array<std::uint64_t, 5> numbers{}; ///< friction, noise, tau, relaxation, bias
    int knots = 0;
    std::string drift, drift_params, drift_table;
    std::vector<double> table_v, table_b;
    bool operator==(const DriftLawInputs&) const = default;
};

/// The inputs of p, or nothing where they do not say the law: a callable
/// (whose behaviour its value does not show) and a table not yet read (whose
/// file may change).
std::optional<DriftLawInputs> drift_law_inputs(const ModelParams& p) {
    if (p.drift_function || (!p.drift_table.empty() && p.drift_table_v.empty())) return std::nullopt;
    DriftLawInputs in;
    in.numbers = {std::bit_cast<std::uint64_t>(p.friction), std::bit_cast<std::uint64_t>(p.noise),
                  std::bit_cast<std::uint64_t>(p.tau), std::bit_cast<std::uint64_t>(p.relaxation),
                  std::bit_cast<std::uint64_t>(p.bias)};
    in.knots = p.knots;
    in.drift = p.drift;
    in.drift_params = p.drift_params;
    in.drift_table = p.drift_table;
    in.table_v = p.drift_table_v;
    in.table_b = p.drift_table_b;
    return in;
}

/// The laws made most recently, newest last: the engines' constants, the
/// thresholds, the step choices, the quadrature, the chain and the corrector
/// of one run all ask for the law of the same inputs, and get the one made
/// first instead of a new one each (a run used to make it 32 times).
struct MadeLaw {
    DriftLawInputs inputs;
    DriftLaw law;
    DriftLawReport report;
};
constexpr std::size_t made_laws_kept = 8; // a sweep's point, its neighbours, a --check-knots pair
std::mutex made_laws_mutex;
std::deque<std::shared_ptr<const MadeLaw>> made_laws;
std::atomic<std::uint64_t> drift_laws_built{0};

} // namespace

DriftLaw make_drift_law(const ModelParams& p, DriftLawReport* report) {
    if (!p.has_drift_law()) return build_drift_law(p, report); // the affine law: nothing to make
    std::optional<DriftLawInputs> inputs = drift_law_inputs(p);
    if (inputs) {
        std::lock_guard lock(made_laws_mutex);
        for (auto it = made_laws.rbegin(); it != made_laws.rend(); ++it)
            if ((*it)->inputs == *inputs) {
                if (report) *report = (*it)->report;
                return (*it)->law;
            }
    }
    // Made outside the lock (a callable may take long); a refusal is not kept.
    auto made = std::make_shared<MadeLaw>();
    made->law = build_drift_law(p, &made->report);
    drift_laws_built.fetch_add(1, std::memory_order_relaxed);
    if (report) *report = made->report;
    if (inputs) {
        made->inputs = std::move(*inputs);
        std::lock_guard lock(made_laws_mutex);
        made_laws.push_back(made);
        if (made_laws.size() > made_laws_kept) made_laws.pop_front();
    }
    return made->law;
}

std::uint64_t drift_laws_made() { return drift_laws_built.load(std::memory_order_relaxed); }

std::vector<std::string> drift_expression_constants(const std::string& text) {
    mu::Parser parser;
    double v = 0.0;
    std::vector<std::unique_ptr<double>> spares;
    std::vector<std::string> names;
    try {
        parser.DefineVar("v", &v);
        parser.SetVarFactory(&spare_variable, &spares);
        parser.SetExpr(text);
        for (const auto& [name, where] : parser.GetUsedVar())
            if (name != "v") names.push_back(name);
    } catch (const mu::Parser::exception_type& e) {
        fail("drift", "cannot read \"" + text + "\": " + e.GetMsg());
    }
    return names;
}

std::string drift_params_without(const std::string& params, const std::string& name) {
    std::stringstream in(params);
    std::string item, out;
    while (std::getline(in, item, ',')) {
        item = trim(item);
        // An item without '=' is kept, for the law's parser to refuse by name.
        if (item.find('=') == std::string::npos || trim(item.substr(0, item.find('='))) != name)
            out += (out.empty() ? "" : ",") + item;
    }
    return out;
}

std::string drift_params_with(const std::string& params, const std::string& name, double value) {
    const std::string others = drift_params_without(params, name);
    return others + (others.empty() ? "" : ",") + name + "=" + format_setting(value);
}

std::string drift_law_note(const DriftLawReport& law) {
    return "drift law (" + law.source + ") " + law.text + ": interpolated on " + std::to_string(law.knots) +
           " knots over [" + detail::format_number(law.lower, 4) + ", " + detail::format_number(law.upper, 4) +
           "] m/s, off by at most " + detail::format_number(law.interpolation_error, 2) + " m s^-2";
}

} // namespace stickslip
