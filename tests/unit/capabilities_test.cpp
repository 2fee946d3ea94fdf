// SPDX-License-Identifier: BSD-3-Clause
// The capability table of ARCHITECTURE.md ("Capabilities"), held to the code.
//
// The table (between <!-- capabilities:begin --> and <!-- capabilities:end -->)
// says, for every engine or scheme, noise and command, whether the request is
// accepted ("yes"), refused with InvalidParameter ("refused", whose note names
// the setting: "- [1] `--tau`: ..."), or accepted with tau ignored
// ("white-limit"). This test builds each cell's request with small, valid
// settings through the public API and asks its validate(); no sample is
// drawn (`analytic`, which has no samples, also computes its stationary
// quadratures, to see whether it ignores tau), so the whole table takes
// under 0.1 s. A failure names the cell and, where something threw, the
// exception's setting and text: change the table or the code, whichever is
// wrong.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "stickslip/bruteforce.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/observables.hpp"
#include "stickslip/spectrum.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/white_noise.hpp"

#ifndef STICKSLIP_SOURCE_DIR
#error "tests/CMakeLists.txt defines STICKSLIP_SOURCE_DIR (the repository root, where ARCHITECTURE.md is)"
#endif

namespace stickslip {
namespace {

const char* const kTableBegin = "<!-- capabilities:begin -->";
const char* const kTableEnd = "<!-- capabilities:end -->";

/// One cell: its row (engine or scheme, noise), column (command) and content.
struct Cell {
    std::string engine, noise, command;
    std::string value; ///< "yes" | "refused" | "white-limit" (anything else is an error)
    int note = 0;      ///< the [N] after the value; 0: none
    std::string name() const { return "(" + engine + ", " + noise + ", " + command + ")"; }
};

struct Table {
    std::vector<std::string> commands;        ///< the header's columns after "engine / scheme" and "noise"
    std::vector<Cell> cells;                  ///< row by row
    std::map<int, std::string> note_setting;  ///< note N -> the setting it starts with ("tau"), if any
    std::string error;                        ///< why the table could not be read ("" if it could)
};

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

/// The cells of a Markdown table row "| a | b |" -> {"a", "b"}.
std::vector<std::string> split_row(const std::string& line) {
    std::vector<std::string> out;
    std::string t = trim(line);
    if (t.size() < 2 || t.front() != '|' || t.back() != '|') return out;
    t = t.substr(1, t.size() - 2);
    std::stringstream ss(t);
    std::string part;
    while (std::getline(ss, part, '|')) out.push_back(trim(part));
    return out;
}

/// "refused [2]" -> ("refused", 2); "yes" -> ("yes", 0).
std::pair<std::string, int> split_cell(const std::string& text) {
    const auto open = text.find('[');
    if (open == std::string::npos) return {trim(text), 0};
    const auto close = text.find(']', open);
    const std::string number = text.substr(open + 1, close == std::string::npos ? std::string::npos : close - open - 1);
    return {trim(text.substr(0, open)), std::atoi(number.c_str())};
}

Table read_table(const std::string& path) {
    Table table;
    std::ifstream in(path);
    if (!in) {
        table.error = "cannot open " + path;
        return table;
    }
    std::string line;
    bool inside = false, ended = false, header = false;
    while (std::getline(in, line)) {
        if (trim(line) == kTableBegin) {
            inside = true;
            continue;
        }
        if (trim(line) == kTableEnd) {
            ended = inside;
            break;
        }
        if (!inside) continue;
        const std::string t = trim(line);
        if (t.rfind("- [", 0) == 0) { // a note: "- [N] `--setting`: reason"
            const int n = std::atoi(t.c_str() + 3);
            const auto flag = t.find("`--");
            const auto close = t.find('`', flag + 1);
            const auto bracket = t.find(']');
            // The setting counts only when it is the note's first word.
            if (flag != std::string::npos && close != std::string::npos && bracket != std::string::npos &&
                trim(t.substr(bracket + 1, flag - bracket - 1)).empty())
                table.note_setting[n] = t.substr(flag + 3, close - flag - 3);
            continue;
        }
        const std::vector<std::string> row = split_row(line);
        if (row.empty()) continue;
        if (!header) {
            if (row.size() < 3 || row[0] != "engine / scheme" || row[1] != "noise") {
                table.error = "the table's header must start with '| engine / scheme | noise |', got: " + line;
                return table;
            }
            table.commands.assign(row.begin() + 2, row.end());
            header = true;
            continue;
        }
        if (row[0].rfind("---", 0) == 0) continue; // the separator line
        if (row.size() != table.commands.size() + 2) {
            table.error = "a row has " + std::to_string(row.size()) + " cells, the header " +
                          std::to_string(table.commands.size() + 2) + ": " + line;
            return table;
        }
        for (std::size_t k = 0; k < table.commands.size(); ++k) {
            const auto [value, note] = split_cell(row[k + 2]);
            table.cells.push_back(Cell{row[0], row[1], table.commands[k], value, note});
        }
    }
    if (!ended) table.error = std::string("no table between ") + kTableBegin + " and " + kTableEnd + " in " + path;
    else if (table.cells.empty()) table.error = "the capability table has no rows";
    return table;
}

const Table& architecture_table() {
    static const Table table = read_table(std::string(STICKSLIP_SOURCE_DIR) + "/ARCHITECTURE.md");
    return table;
}

// ---- the rows and columns, as requests -------------------------------------------

/// The engine settings of a row's "engine / scheme"; false for a name this test does not know.
bool engine_of(const std::string& name, EngineSettings& s) {
    s = EngineSettings{};
    if (name == "inclusion + resolvent") s.scheme = Scheme::Resolvent;
    else if (name == "inclusion + event") s.scheme = Scheme::Event;
    else if (name == "pdmp") s.engine = Engine::Pdmp;
    else if (name == "kolmogorov") s.engine = Engine::Kolmogorov;
    else return false;
    return true;
}

/// The drift law of the rows "..., any b(v)": a non-affine law (quadratic drag).
const char* const kAnyLaw = "0.3 - v*abs(v)";

/// Static friction over friction in the requests made below: 1 (unset) for
/// the table's cells, 1.5 for the test that a static band changes no cell.
double g_static_ratio = 1.0;

/// Sets the static friction of p from g_static_ratio (unset at 1).
void set_static_friction(ModelParams& p) {
    if (g_static_ratio != 1.0) p.static_friction = g_static_ratio * p.friction;
}

/// tau [s] of a row's noise: white 0, coloured the default (the paper's Fig. 2
/// case, 0.5 s); `law`: the row is "white, any b(v)" or "coloured, any b(v)".
bool tau_of(const std::string& noise, double& tau, bool& law) {
    const std::string suffix = ", any b(v)";
    law = noise.size() > suffix.size() && noise.compare(noise.size() - suffix.size(), suffix.size(), suffix) == 0;
    const std::string kind = law ? noise.substr(0, noise.size() - suffix.size()) : noise;
    if (kind == "white") tau = 0.0;
    else if (kind == "coloured") tau = ModelParams{}.tau;
    else return false;
    return true;
}

/// Validates a command's request for an engine and a tau, with small, valid settings.
using Validate = std::function<void(const EngineSettings&, double tau, bool law)>;

/// The settings that make a run small are sampling settings, which the
/// Kolmogorov engine refuses (it samples nothing): with it, `fill` is skipped
/// but for the grid of a sweep.
template <class R, class Fill>
std::pair<std::string, Validate> simulated(Fill fill) {
    return {R::command, [fill](const EngineSettings& e, double tau, bool law) {
                R r;
                r.engine = e;
                r.params.tau = tau;
                if (law) r.params.drift = kAnyLaw;
                set_static_friction(r.params);
                r.control.threads = 1;
                if (e.engine != Engine::Kolmogorov) fill(r);
                if constexpr (std::is_same_v<R, SweepRequest>) {
                    r.noises = {r.params.noise};
                    r.taus = {r.params.tau};
                }
                validate(r);
            }};
}

/// The request of `analytic`: it has no engine, and tau goes into its params.
/// Stationary references only (times would add a Fokker-Planck solve, ~0.6 s).
WhiteNoiseRequest white_noise_request(double tau, bool law) {
    WhiteNoiseRequest r;
    r.params.tau = tau;
    if (law) r.params.drift = kAnyLaw;
    set_static_friction(r.params);
    return r;
}

/// Every command's validation, by the command's own name (Request::command).
const std::map<std::string, Validate>& validations() {
    static const std::map<std::string, Validate> all = {
        simulated<DiffusivityRequest>([](DiffusivityRequest& r) { r.excursions = 64; }),
        simulated<BruteForceRequest>([](BruteForceRequest& r) {
            r.horizon = 1.0;
            r.trajectories = 64;
        }),
        simulated<SweepRequest>([](SweepRequest& r) {
            r.noises = {r.params.noise};
            r.taus = {r.params.tau};
            r.excursions = 64;
        }),
        simulated<DensityRequest>([](DensityRequest& r) {
            r.excursions = 64;
            r.bins.count = 10;
        }),
        simulated<CorrelationRequest>([](CorrelationRequest& r) {
            r.excursions = 64;
            r.lags = 5;
            r.max_lag = 0.1;
        }),
        simulated<MomentsRequest>([](MomentsRequest& r) { r.trajectories = 64; }),
        simulated<TrajectoryRequest>([](TrajectoryRequest& r) { r.index = 0; }),
        simulated<SpectrumRequest>([](SpectrumRequest& r) { r.excursions = 64; }),
        {WhiteNoiseRequest::command,
         [](const EngineSettings&, double tau, bool law) { validate(white_noise_request(tau, law)); }},
    };
    return all;
}

/// What validate() did: nothing, or threw InvalidParameter (setting, text).
struct Outcome {
    bool refused = false;
    std::string setting, text;
};

Outcome outcome_of(const Validate& v, const EngineSettings& e, double tau, bool law) {
    try {
        v(e, tau, law);
        return {};
    } catch (const InvalidParameter& x) {
        return {true, x.parameter(), x.what()};
    }
}

/// What a cell asks: its engine, tau, law and command's validation.
struct CellRequest {
    EngineSettings engine;
    double tau = 0;
    bool law = false;
    Validate validate;
};

/// The request of cell c; false for an engine, noise or command this test does not know.
bool request_of(const Cell& c, CellRequest& q) {
    const auto v = validations().find(c.command);
    if (!engine_of(c.engine, q.engine) || !tau_of(c.noise, q.tau, q.law) || v == validations().end()) return false;
    q.validate = v->second;
    return true;
}

// ---- the tests ----------------------------------------------------------------------

TEST(Capabilities, TableCoversEveryEngineNoiseAndCommand) {
    const Table& t = architecture_table();
    ASSERT_EQ(t.error, "");
    std::set<std::string> commands(t.commands.begin(), t.commands.end());
    EXPECT_EQ(commands.size(), t.commands.size()) << "a command appears twice in the table's header";
    for (const auto& [command, v] : validations())
        EXPECT_TRUE(commands.count(command)) << "ARCHITECTURE.md's capability table has no column '" << command << "'";
    for (const std::string& c : t.commands)
        EXPECT_TRUE(validations().count(c)) << "the table's column '" << c << "' is no command this test knows";

    const std::set<std::pair<std::string, std::string>> rows_expected = {
        {"inclusion + resolvent", "white"}, {"inclusion + resolvent", "coloured"},
        {"inclusion + event", "white"},     {"inclusion + event", "coloured"},
        {"pdmp", "white"},                  {"pdmp", "coloured"},
        {"kolmogorov", "white"},            {"kolmogorov", "coloured"},
        {"inclusion + resolvent", "white, any b(v)"}, {"inclusion + resolvent", "coloured, any b(v)"},
        {"inclusion + event", "white, any b(v)"},     {"inclusion + event", "coloured, any b(v)"},
        {"pdmp", "white, any b(v)"},                  {"pdmp", "coloured, any b(v)"},
        {"kolmogorov", "white, any b(v)"},            {"kolmogorov", "coloured, any b(v)"},
    };
    std::set<std::pair<std::string, std::string>> rows;
    for (const Cell& c : t.cells) rows.insert({c.engine, c.noise});
    EXPECT_EQ(rows, rows_expected) << "the table's rows must be every engine or scheme with white and coloured noise, with the affine "
                                     "drift law and with any b(v)";

    for (const Cell& c : t.cells) {
        EXPECT_TRUE(c.value == "yes" || c.value == "refused" || c.value == "white-limit")
            << "cell " << c.name() << ": '" << c.value << "' is not yes, refused or white-limit";
        if (c.value == "refused") {
            EXPECT_TRUE(t.note_setting.count(c.note))
                << "cell " << c.name() << ": a refusal needs a note [N] that starts with the refused `--setting`";
        }
        if (c.value == "white-limit") {
            EXPECT_EQ(c.command, WhiteNoiseRequest::command)
                << "cell " << c.name() << ": white-limit is what `analytic` does with coloured noise only";
        }
    }
}

TEST(Capabilities, StaticFrictionChangesNoCell) {
    // A static friction above the friction (issue 46) runs wherever the
    // one-coefficient model runs and is refused where it is refused, for the
    // same setting: the table's cells hold for it too (ARCHITECTURE.md).
    const Table& t = architecture_table();
    ASSERT_EQ(t.error, "");
    int checked = 0;
    for (const Cell& c : t.cells) {
        CellRequest q;
        if (!request_of(c, q)) continue;
        g_static_ratio = 1.0;
        const Outcome plain = outcome_of(q.validate, q.engine, q.tau, q.law);
        g_static_ratio = 1.5;
        const Outcome banded = outcome_of(q.validate, q.engine, q.tau, q.law);
        g_static_ratio = 1.0;
        ++checked;
        EXPECT_EQ(banded.refused, plain.refused) << "cell " << c.name() << ": " << banded.text;
        EXPECT_EQ(banded.setting, plain.setting) << "cell " << c.name() << ": " << banded.text;
    }
    EXPECT_EQ(checked, static_cast<int>(t.cells.size()));
}

TEST(Capabilities, EveryCellIsWhatValidateDoes) {
    const Table& t = architecture_table();
    ASSERT_EQ(t.error, "");
    int checked = 0;
    for (const Cell& c : t.cells) {
        CellRequest q;
        if (!request_of(c, q)) {
            ADD_FAILURE() << "cell " << c.name() << ": unknown engine, noise or command";
            continue;
        }
        const EngineSettings& engine = q.engine;
        const double tau = q.tau;
        const bool law = q.law;
        const Outcome o = outcome_of(q.validate, engine, tau, law);
        ++checked;
        if (c.value == "refused") {
            if (!o.refused) {
                ADD_FAILURE() << "cell " << c.name() << " says refused, but validate() accepted the request";
                continue;
            }
            const auto note = t.note_setting.find(c.note);
            if (note != t.note_setting.end()) {
                EXPECT_EQ(o.setting, note->second)
                    << "cell " << c.name() << " says refused [" << c.note << "] for --" << note->second
                    << ", but validate() refused --" << o.setting << ": " << o.text;
            }
        } else if (o.refused) {
            ADD_FAILURE() << "cell " << c.name() << " says " << c.value
                          << ", but validate() threw InvalidParameter --" << o.setting << ": " << o.text;
        } else if (c.command == WhiteNoiseRequest::command) {
            // `analytic` is accepted whatever tau; the table says whether it
            // ignores tau (white-limit: the references of tau = 0), which its
            // result shows (quadratures only, a few milliseconds).
            const WhiteNoiseResult given = compute_white_noise(white_noise_request(tau, law));
            const bool ignores_tau = tau > 0 && given.request.params.tau == 0.0;
            EXPECT_EQ(c.value == "white-limit", ignores_tau)
                << "cell " << c.name() << " says " << c.value << ", but compute_white_noise "
                << (ignores_tau ? "ignores" : "uses") << " tau " << tau;
            if (ignores_tau) {
                const WhiteNoiseResult white = compute_white_noise(white_noise_request(0.0, law));
                EXPECT_EQ(given.reference.diffusivity, white.reference.diffusivity) << "cell " << c.name();
                EXPECT_EQ(given.reference.mobility, white.reference.mobility) << "cell " << c.name();
                EXPECT_EQ(given.reference.variance, white.reference.variance) << "cell " << c.name();
            }
        }
    }
    EXPECT_EQ(checked, static_cast<int>(t.cells.size()));
}

} // namespace
} // namespace stickslip
