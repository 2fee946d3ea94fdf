// The output contract of every subcommand: --format table|json|csv, and
// --output FILE written atomically (a temporary file next to it, renamed into
// place when the run succeeds; a run that fails leaves an existing file
// untouched and nothing else behind).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace stickslip::cli {

/// --format, --output, --quiet.
struct OutputFlags {
    std::string format = "table";
    std::string output;
    bool quiet = false;
};

void add_output_flags(CLI::App* app, OutputFlags& o);

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

} // namespace stickslip::cli
