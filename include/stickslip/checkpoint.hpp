// SPDX-License-Identifier: BSD-3-Clause
// stickslip/checkpoint.hpp -- a run's completed work, kept so that a killed
// run can be resumed and its result is the uninterrupted run's, bit for bit.
//
// Why it can be exact: every run is a fixed sequence of calls of the block
// driver (sample_runs.hpp) -- one for a plain run, one per batch of a
// precision-on-demand run, one per point of a sweep, a pilot and a main run
// for a density -- and each call's statistics are exact, order-free sums
// (moment_sums.hpp) of blocks of 64 samples. The driver completes blocks in
// rounds and, after each round, hands the journal the call's state: how many
// blocks (a prefix, in index order) are done, the exact sums of exactly those
// blocks as 64-bit words, and a few integer counts. That is all a run's
// result depends on besides its settings, so a resumed run restores each
// finished call, continues the unfinished one at its first undone block, and
// makes every decision (the next batch size, the next point) from the same
// numbers. Thread and process counts leave no trace in the sums, so they may
// differ on either side.
//
// The file (JSON) names its format and version, the program version and
// revision, the command and every setting of the run except the thread count;
// a checksum covers the rest. --resume refuses, with one line saying what
// differs, a file that is not a checkpoint, is truncated or corrupted, comes
// from another format or program version, or from other settings. It is
// written atomically (detail/atomic_file.hpp: a temporary in its folder,
// unnamed where the system allows, renamed over it), by the first process of
// a distributed run only.
//
// Nothing at the path is destroyed: a link's target is what gets written, a
// device, FIFO, socket or directory is refused, and so is an existing file
// that is not a checkpoint of this very run (another run's saved work), unless
// it is the file --resume continues. A write that fails during the run (a full
// disk) is a warning, not the end of the run: the checkpoint is insurance, the
// result is what was asked for.
#pragma once

/// \file
/// Checkpoints: a run's completed work, saved so that a killed run resumes to
/// the uninterrupted result, bit for bit. The comment at the top of this header
/// explains the design.

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "stickslip/engine.hpp"
#include "stickslip/errors.hpp"
#include "stickslip/setting.hpp"

namespace stickslip {

/// How a front end asks for checkpoints. One definition of the help texts
/// (the CLI's flags and the Python keywords use them).
struct CheckpointOptions {
    std::string path;    ///< write the run's state here ("" = no checkpoints)
    double every = 60.0; ///< seconds between writes (and one at the end)
    std::string resume;  ///< continue the run whose state is in this file ("" = start afresh)
    /// Called with one line (naming the path, not the front end's option)
    /// when a write fails during the run (once, until a write succeeds again,
    /// which is said too) and when a run starts afresh over a checkpoint of
    /// its own; empty: the line goes to stderr as "stickslip: warning:
    /// checkpoint: LINE".
    std::function<void(const std::string&)> warn;

    /// Help text of the `path` option (--checkpoint FILE, checkpoint=).
    static constexpr const char* path_help =
        "write the run's state to FILE (atomically) every --checkpoint-every seconds and at the end, so that "
        "--resume FILE can continue it after a kill; the resumed result is identical to an uninterrupted run's. "
        "FILE must be a regular file or a new one (a symlink's target is written), and an existing FILE must be "
        "a checkpoint of this same run or the --resume file; a write that fails during the run is a warning";
    /// Help text of the `every` option (--checkpoint-every).
    static constexpr const char* every_help = "seconds between checkpoint writes (> 0)";
    /// Help text of the `resume` option (--resume FILE, resume=).
    static constexpr const char* resume_help =
        "continue the run saved in FILE (from --checkpoint); the settings must be the same (threads and process "
        "count may differ); refused if the file is from other settings, another version, truncated or corrupted. "
        "With --checkpoint FILE naming the same file, a missing FILE starts the run afresh (one command line for "
        "the first run and every restart)";
};

/// The settings of a run as (name, text) pairs, in the request's order,
/// without the thread count: what a checkpoint must match.
template <class Request>
std::vector<std::pair<std::string, std::string>> checkpoint_identity(Request& request) {
    std::vector<std::pair<std::string, std::string>> out;
    visit_settings(request, [&](auto&& field, const SettingInfo& info) {
        if (std::string(info.name) != "threads") out.emplace_back(info.name, format_setting(field));
    });
    // The table file's contents, not only its path: a resume with a changed
    // table ran another law (D 3.8 times off, issue 50).
    if constexpr (requires { request.params.drift_table_digest; })
        if (!request.params.drift_table_digest.empty())
            out.emplace_back("drift-table-digest", request.params.drift_table_digest);
    return out;
}

/// The journal of one run (see the top of the file). Not thread-safe: the
/// block driver uses it from the thread that called it, between rounds.
class RunJournal {
public:
    /// The state of one call of the block driver.
    struct Call {
        std::uint64_t samples = 0;     ///< samples the call was asked for
        std::uint64_t first_index = 0; ///< its first sample index
        std::uint64_t blocks_done = 0; ///< blocks [0, blocks_done) are in `words`
        /// Every block of the call is done (its sums are final).
        bool complete = false;
        std::vector<std::uint64_t> counts; ///< the driver's integer totals
        std::vector<std::uint64_t> words;  ///< the exact sums' words
    };

    /// A journal for `command` with these settings; `options.path` empty: keep
    /// the state in memory only (nothing is written). Validates the options
    /// (InvalidParameter "checkpoint-every"), checks `options.path`
    /// (InvalidParameter "checkpoint": a directory, a device, FIFO or socket,
    /// a file that is neither a checkpoint of this run nor the resume file),
    /// reads `options.resume` when given (InvalidParameter "resume" with one
    /// line when it cannot be used), and writes a first checkpoint at once, so
    /// that a path that cannot be written fails before any work
    /// (InvalidParameter "checkpoint").
    RunJournal(std::string command, std::vector<std::pair<std::string, std::string>> settings,
               CheckpointOptions options, unsigned rank = 0);

    /// The next call's state: the saved one when resuming (InvalidParameter
    /// "resume" if it was for another call), else a new, empty one.
    Call& begin_call(std::uint64_t samples, std::uint64_t first_index, std::size_t words);
    /// After a round: the call's state changed; writes the file when due.
    void updated();
    /// Writes the file now (at the end of a run, or when interrupted). A
    /// failure does not throw: it is a warning (CheckpointOptions::warn) and
    /// the run goes on.
    void write();

    /// Seconds between writes (the block driver's rounds are no longer).
    double every() const { return options_.every; }
    /// True when the journal continues a saved run.
    bool resumed() const { return !options_.resume.empty(); }
    /// True when this journal writes a file: a path was given and this is the
    /// first process (rank 0) of the run.
    bool writes() const { return !options_.path.empty() && rank_ == 0; }

    /// The file's text for the current state (for tests).
    std::string serialise() const;

private:
    void check_path();
    void read(const std::string& file);
    /// Reads `file` into `calls`; "" or why it cannot continue this run.
    std::string load(const std::string& file, std::deque<Call>& calls) const;
    void store();
    void warn(const std::string& line) const;

    std::string command_;
    std::vector<std::pair<std::string, std::string>> settings_;
    CheckpointOptions options_;
    std::string target_; ///< options_.path with its links followed
    unsigned rank_;
    bool failing_ = false; ///< the last write failed
    std::deque<Call> calls_;
    std::size_t next_ = 0;
    std::chrono::steady_clock::time_point last_write_;
};

/// Checks the options (InvalidParameter "checkpoint-every" for a bad period,
/// whether or not a checkpoint is asked for).
void validate(const CheckpointOptions& options);

/// The journal a front end gives a run of `request` (a request with
/// `resumable`, after its process split is set: only the first process
/// writes), or nullptr when the options ask for neither a checkpoint nor a
/// resume. Point request.control.journal at it, run, then write() it.
/// InvalidParameter ("checkpoint" or "resume") for the Kolmogorov engine,
/// which has no samples to keep.
template <class Request>
std::unique_ptr<RunJournal> make_journal(Request& request, const CheckpointOptions& options) {
    validate(options);
    if (options.path.empty() && options.resume.empty()) return nullptr;
    if constexpr (requires { request.engine.engine; }) {
        // A grid solver's run has no samples to keep, and takes seconds.
        if (!samples(request.engine))
            throw InvalidParameter(options.path.empty() ? "resume" : "checkpoint",
                                   "the kolmogorov engine samples nothing, so there is nothing to checkpoint or "
                                   "resume: run without --checkpoint and --resume");
    }
    return std::make_unique<RunJournal>(Request::command, checkpoint_identity(request), options,
                                        request.control.rank);
}

} // namespace stickslip
