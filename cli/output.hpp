// SPDX-License-Identifier: BSD-3-Clause
// The output contract of every subcommand: --format table|json|csv, and
// --output FILE. A regular file (or a new one) is written atomically
// (stickslip/detail/atomic_file.hpp, the writer checkpoints use too): a
// temporary file in its folder, unnamed where the system allows, renamed into
// place when the run succeeds, so a run that fails or is killed, even by
// SIGKILL, leaves an existing file untouched and nothing else behind; the
// file keeps its mode and owner, and a symlink stays a link (its target is
// what gets replaced). Anything else (a device such as /dev/null or
// a terminal, a FIFO, a socket, /dev/stdout) is written through, as any other
// program would write it: replacing it by a regular file would break it.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "stickslip/checkpoint.hpp"
#include "stickslip/detail/atomic_file.hpp"
#include "stickslip/report.hpp"

namespace stickslip::cli {

/// --format, --output, --quiet.
struct OutputFlags {
    std::string format = "table";
    std::string output;
    bool quiet = false;                 ///< known after read_output_flags()
    CLI::Option* quiet_flag = nullptr; ///< --quiet, read as every boolean flag (setting_flags.hpp)
};

void add_output_flags(CLI::App* app, OutputFlags& o);
/// After parsing: sets `quiet` from --quiet (InvalidParameter "quiet" for a
/// value that is not a boolean's).
void read_output_flags(OutputFlags& o);

/// Validates --format and --output before any work starts (so a bad path
/// fails in a second, not after an hour); for a regular file it opens the
/// temporary in the target's folder there. commit() writes the text: renames the
/// temporary into place, or writes a device, FIFO or descriptor directly.
/// A run that fails (any exception, or a terminating signal) leaves nothing
/// behind.
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
    enum class Sink {
        standard_output, ///< no --output
        atomic,          ///< a regular or new file at target_, via file_
        direct,          ///< a device, FIFO or socket at target_, opened at commit
        descriptor,      ///< /dev/stdout, /dev/fd/N...: this process's descriptor_
    };
    void write_all(int fd, const std::string& text) const;
    void commit_atomic(const std::string& text);
    void discard() noexcept;

    std::string format_, path_, target_;
    Sink sink_ = Sink::standard_output;
    std::unique_ptr<detail::AtomicFile> file_;
    int descriptor_ = -1;
    bool quiet_ = false;
};

/// Refuses (InvalidParameter "output", before any work) an --output that is
/// the --checkpoint or the --resume file, however spelt (links, "./"): the
/// result would replace the saved state of the run.
void refuse_shared_paths(const OutputFlags& output, const CheckpointOptions& checkpoint);

/// Refuses (InvalidParameter "output") an --output that is one of the run's
/// input files (`inputs`: the flag that names each, and its path), or a link
/// to one: the result would replace the file it was computed from.
void refuse_output_over_inputs(const OutputFlags& output,
                               const std::vector<std::pair<std::string, std::string>>& inputs);

/// Removes the named temporary files of this process (the output's and a
/// checkpoint's), if any; async-signal-safe (for a signal handler that is
/// about to end the process).
void remove_output_temporary() noexcept;

/// For its lifetime, every terminating signal left at its default (those
/// another handler took, such as StopOnSignals' SIGINT and SIGTERM, stay
/// theirs) first removes the named temporaries in flight, then ends the
/// process by that very signal as before. Only needed where no unnamed
/// temporary could be had, or in the instant a temporary is being renamed.
class CleanupOnSignals {
public:
    CleanupOnSignals();
    ~CleanupOnSignals();
    CleanupOnSignals(const CleanupOnSignals&) = delete;
    CleanupOnSignals& operator=(const CleanupOnSignals&) = delete;
};

/// Picks the rendering for the format of `out` and commits it.
template <class Result>
void emit(Output& out, const Result& r) {
    check_finite_result(to_json(r, -1)); // exit 3 rather than NaN, inf or null with exit 0
    if (out.format() == "json") out.commit(to_json(r), {});
    else if (out.format() == "csv") out.commit(to_csv(r), r.warnings);
    else out.commit(to_table(r), {});
}

} // namespace stickslip::cli
