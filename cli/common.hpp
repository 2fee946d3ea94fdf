// Shared pieces of the `stickslip` command: the model/engine/run flags every
// computing subcommand takes, strict number parsing (no silent truncation), the
// output contract (--format table|json|csv, --output FILE written atomically),
// and the progress line. Subcommands live in commands.cpp.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "stickslip/diffusivity.hpp"

namespace stickslip::cli {

/// Exit codes: 0 ok, 1 unexpected failure (I/O, internal), 2 bad input,
/// 3 untrustworthy run (runaway excursions).
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitCapped = 3;

/// Model, engine and run flags as strings, parsed after CLI11 so that every
/// error names its flag. Defaults are the paper's Fig. 2 case.
struct ModelFlags {
    std::string friction = "3.84", noise = "5", tau = "0.5", relaxation = "0.067", bias = "0.342";
    std::string engine = "inclusion", dt = "1e-4", grid = "0.125", lattice_bound = "0";
    std::string seed = "1", threads = "0", level = "0.95", max_steps = "200000000";
    std::string stop_rule = "auto", white_level = "0";
};

/// --format, --output, --quiet.
struct OutputFlags {
    std::string format = "table";
    std::string output;
    bool quiet = false;
};

/// A value option shown with its type and its default in --help.
CLI::Option* add_value(CLI::App* app, const std::string& name, std::string& value, const std::string& type,
                       const std::string& help);

/// What add_model_flags registers: `physics` = friction/noise/tau/relaxation/
/// bias; `engine` = engine, dt, grid, lattice bound, stop rule, white level,
/// max steps; `run` = seed, threads, level.
struct FlagSet {
    bool physics = true, tau = true, engine = true, run = true;
};
void add_model_flags(CLI::App* app, ModelFlags& f, FlagSet which = {});
void add_output_flags(CLI::App* app, OutputFlags& o);

double to_double(const std::string& name, const std::string& s);
std::uint64_t to_count(const std::string& name, const std::string& s);
std::uint64_t to_seed(const std::string& s);
/// Comma-separated numbers, or lo:hi:n for n values from lo to hi, spaced
/// evenly in log (lo, hi > 0) or, with linear = true, evenly.
std::vector<double> to_list(const std::string& name, const std::string& s, bool linear = false);

/// Fills params, engine settings, seed and threads, and the level.
void fill(const ModelFlags& f, ModelParams& p, EngineSettings& e, RunControl& c, double& level);
void fill_physics(const ModelFlags& f, ModelParams& p);

/// Validates --format and, when --output is given, opens the temporary file
/// next to it before any work starts (so a bad path fails in a second, not
/// after an hour). commit() writes the text and renames it into place; a run
/// that fails leaves nothing behind.
class Output {
public:
    explicit Output(const OutputFlags& o);
    ~Output();
    Output(const Output&) = delete;
    Output& operator=(const Output&) = delete;

    const std::string& format() const { return format_; }
    /// Writes the chosen rendering; warnings go to stderr (as "note:" lines)
    /// for csv, whose file has no place for them.
    void commit(const std::string& text, const std::vector<std::string>& warnings);

private:
    std::string format_, path_, temp_;
    int fd_ = -1;
    bool quiet_ = false;
};

/// Picks the rendering for the format of `out` and commits it.
template <class Result>
void emit(Output& out, const Result& r) {
    if (out.format() == "json") out.commit(to_json(r), {});
    else if (out.format() == "csv") out.commit(to_csv(r), r.warnings);
    else out.commit(to_table(r), {});
}

/// Progress line on stderr, only when it is a terminal and not --quiet:
/// samples done of total, rate, time left; with level > 0 (long excursions)
/// also the current D and the relative half-width of its interval.
std::function<bool(const Progress&)> progress_line(bool quiet, const std::string& what, double level = 0.0);

/// The conventions footer of every --help.
extern const char* const kConventions;

} // namespace stickslip::cli
