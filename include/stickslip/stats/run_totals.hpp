// SPDX-License-Identifier: BSD-3-Clause
// stickslip/stats/run_totals.hpp -- the raw outcome of a Monte Carlo run.
//
// Samples are grouped in fixed blocks of `block_size` consecutive indices
// (independent of the thread count); each block's moments are computed by one
// thread in index order, then added into exact, order-free sums
// (moment_sums.hpp, control_variate.hpp) as soon as the block is done: the
// totals of a run are the same bits for any thread count, process split,
// reduction order and resume point.
#pragma once

/// \file
/// A run's totals: its exact sums and counts. The comment at the top of this
/// header explains the design.

#include <cstdint>
#include <string>

#include "stickslip/stats/control_variate.hpp"
#include "stickslip/stats/estimators.hpp"
#include "stickslip/stats/moment_sums.hpp"
#include "stickslip/result_fields.hpp"

namespace stickslip {

/// Samples per block: the unit of work and of deterministic merging.
inline constexpr std::uint64_t block_size = 64;

/// What a result's threads_from says (RunTotals, and the work block's,
/// RunWork in report.hpp): one text for both.
inline constexpr const char* threads_from_help =
    "how the thread count was chosen: 'option' (the threads setting), else 'hardware', 'affinity', 'cpu-quota' or "
    "'slurm', with '+local-ranks' when shared among MPI ranks, '+blocks' when the blocks were fewer";

/// Raw outcome of a run: the exact sums of (U, t) over completed samples and
/// the centred moments computed from them.
struct RunTotals {
    /// Exact sums of (U, t) (x = displacement U [m], y = duration t [s]) over
    /// the completed samples, capped ones excluded.
    ExactBivariateSums sums;
    BivariateMoments moments; ///< sums.moments()
    /// Samples asked for (completed, capped and, if interrupted, not run).
    std::uint64_t requested = 0;
    std::uint64_t capped = 0; ///< samples dropped by the runaway guard
    std::uint64_t work = 0;   ///< steps or events, all samples
    /// Wall time of the run [s]; a resumed run counts only this invocation.
    double seconds = 0.0;
    /// Worker threads used: RunControl::threads (0: default_threads()), at
    /// most one per block of this process.
    unsigned threads = 1;
    /// How `threads` was chosen: ThreadChoice::from ("option" for
    /// RunControl::threads > 0, else "hardware", "affinity", "cpu-quota",
    /// "slurm", each possibly with "+local-ranks"), with "+blocks" when this
    /// process had fewer blocks than that.
    std::string threads_from;
    bool interrupted = false; ///< stopped early (RunControl::stop): the sums are of a prefix of whole blocks
    std::uint64_t resumed = 0; ///< samples restored from a checkpoint rather than computed
    /// Long excursions run with a corrector (run_long_excursions' g): the
    /// exact sums of (U, t, M, M^2 - Q) over the completed excursions (empty
    /// otherwise).
    ControlVariateSums control_variate;

    /// Adds the cost of `other`, a run made for this one (a batch of it, its
    /// control variate's pilot): its work, wall time and resumed samples.
    void add_cost(const RunTotals& other) {
        work += other.work;
        seconds += other.seconds;
        resumed += other.resumed;
    }

    /// The counts a report gives, in report order (result_fields.hpp): the
    /// capped samples beside the estimates; the rest in the report's work.
    template <class Visit> static constexpr void fields(Visit&& visit) {
        using S = RunTotals;
        visit(&S::capped, FieldInfo{"capped", "", "samples dropped by the runaway guard (max_steps)"});
        visit(&S::work, FieldInfo{"work", "", "steps (inclusion) or events (pdmp), all samples; the work block's",
                                  FieldForm::NotInBlock});
        visit(&S::seconds, FieldInfo{"seconds", "s", "wall time of the run; the work block's", FieldForm::NotInBlock});
        visit(&S::threads_from, FieldInfo{"threads_from", "", threads_from_help, FieldForm::NotInBlock});
        visit(&S::resumed, FieldInfo{"resumed", "",
                                     "samples restored from a checkpoint (resume=) rather than computed; the work "
                                     "block's resumed_samples",
                                     FieldForm::NotInBlock});
    }
};

} // namespace stickslip
