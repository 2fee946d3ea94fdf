// SPDX-License-Identifier: BSD-3-Clause
// stickslip/prepared_engine.hpp -- the engine of a run, prepared once.
//
// A run validates its model and engine settings once and builds the chosen
// engine's constants (prepare_engine, run.hpp): the constants are one
// alternative of a std::variant, so that a run holds exactly the engine it
// runs, and the library's code visits it once per run (src/engines/
// visit_engine.hpp), never per step: the kernels stay non-virtual, vectorised
// and compiled for the GPU as they are. Adding an engine adds an alternative
// here (ARCHITECTURE.md, "Add an engine").
//
// This header includes the kernels' constants; the requests' headers
// (diffusivity.hpp, observables.hpp, ...) do not include it.
#pragma once

/// \file
/// The engine of a run, prepared once: its constants as a variant. The
/// comment at the top of this header explains the design.

#include <string>
#include <variant>
#include <vector>

#include "stickslip/engine.hpp"
#include "stickslip/kernels/event_scheme.hpp"
#include "stickslip/kernels/pdmp.hpp"
#include "stickslip/kernels/resolvent.hpp"
#include "stickslip/params.hpp"
#include "stickslip/run.hpp"

namespace stickslip {

/// The constants of the engine a run uses: the inclusion engine with its
/// resolvent or event scheme, or the PDMP engine.
using EngineConstants = std::variant<ResolventConstants, EventConstants, PdmpConstants>;

/// The engine of a run, prepared once: the chosen engine's (and scheme's)
/// constants and the details a report shows.
struct PreparedEngine {
    /// The model it was prepared for (SI units), with its drift law made once
    /// (model.hpp): whatever runs on this engine takes the law from here.
    Model model;
    /// The engine settings it was prepared from, with --dt auto resolved (the
    /// other resolved choices, e.g. the stop rule, are in `resolved` and the
    /// constants).
    EngineSettings settings;
    /// The constants of the engine (and scheme) that runs.
    EngineConstants constants;
    /// What the constants point to and must outlive them (the event scheme's
    /// laws of each piece of a knots drift law); shared by the copies.
    std::shared_ptr<const void> storage;
    /// What was chosen for the run, for the reports.
    ResolvedEngine resolved;
    /// Notes on the settings found when preparing (a step too coarse for a
    /// trustworthy D): every report of a run on this engine carries them.
    std::vector<std::string> notes;

    /// Frees `storage` (and the model's law) and clears the constants'
    /// pointers into it: the engine keeps what its preparation found (the
    /// parameters, settings, resolved choices, notes) but can no longer run. For keeping the checks of many prepared
    /// points without their laws (a sweep's preparation). Returns whether
    /// there was storage to free.
    bool release_storage();

    /// The constants of engine C, or nullptr when another engine runs.
    template <class C>
    const C* constants_of() const {
        return std::get_if<C>(&constants);
    }
};

} // namespace stickslip
