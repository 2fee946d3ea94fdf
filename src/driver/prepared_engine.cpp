// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/run.hpp"

#include "stickslip/prepared_engine.hpp"

#include <cmath>

#include "core/format.hpp"
#include "stickslip/drift_input.hpp"
#include "stickslip/stats/estimators.hpp"
#include "driver/step_check.hpp" // check_step: the notes of a prepared run
#include "engines/event/event_steps.hpp"
#include "engines/resolvent/resolvent_steps.hpp"

namespace stickslip {

double auto_time_step(const ModelParams& p, Scheme scheme) { return auto_time_step(make_model(p), scheme); }

double auto_time_step(const Model& m, Scheme scheme) {
    return scheme == Scheme::Resolvent ? detail::resolvent_auto_step(m) : detail::event_auto_step(m);
}

namespace {
/// auto_scheme for white noise, which needs no law (nor a check of the model).
Scheme white_noise_scheme(const ModelParams& p, PathUse use) {
    // The white-noise event scheme takes the affine law only.
    if (p.has_drift_law()) return Scheme::Resolvent;
    return use == PathUse::GridSamples ? Scheme::Resolvent : Scheme::Event;
}
} // namespace

Scheme auto_scheme(const ModelParams& p, PathUse use) {
    return p.white() ? white_noise_scheme(p, use) : auto_scheme(make_model(p), use);
}

Scheme auto_scheme(const Model& m, PathUse use) {
    if (m.params.white()) return white_noise_scheme(m.params, use);
    // Near-white noise (tau' below about 1e-4): the event step must resolve
    // tau, the resolvent's follows the white-noise law and is the longer.
    return auto_time_step(m, Scheme::Resolvent) > auto_time_step(m, Scheme::Event) ? Scheme::Resolvent
                                                                                    : Scheme::Event;
}

EngineSettings resolve_engine_settings(const ModelParams& p, EngineSettings s, PathUse use) {
    // The model is made (and checked) only where a step decides: what is
    // resolved without one is resolved so, and refuses nothing.
    if (s.engine != Engine::Inclusion) return s;
    if (s.scheme == Scheme::Auto && p.white()) s.scheme = white_noise_scheme(p, use);
    return s.dt_auto || s.scheme == Scheme::Auto ? resolve_engine_settings(make_model(p), s, use) : s;
}

EngineSettings resolve_engine_settings(const Model& m, EngineSettings s, PathUse use) {
    // The scheme matters to the inclusion engine only (the PDMP's is kept).
    if (s.scheme == Scheme::Auto && s.engine == Engine::Inclusion) s.scheme = auto_scheme(m, use);
    if (s.dt_auto && s.engine == Engine::Inclusion) s.dt = auto_time_step(m, s.scheme);
    return s;
}

PreparedEngine prepare_engine(const ModelParams& p, const EngineSettings& given, const std::atomic<bool>* stop) {
    // Every Monte Carlo path prepares its engine here: the grid solver is
    // chosen above, by the quantities that it can compute.
    if (!samples(given))
        throw InvalidParameter("engine", std::string(kolmogorov_engine_scope) +
                                             ": this command samples paths, use --engine inclusion or pdmp");
    PreparedEngine e;
    e.model = make_model(p); // the one law of the run: every part below takes it from here
    const Model& m = e.model;
    const EngineSettings s = resolve_engine_settings(m, given);
    e.settings = s;
    // Building an engine's constants validates the model, both step settings
    // and how they fit together.
    ResolvedEngine& r = e.resolved;
    if (s.engine == Engine::Pdmp) {
        const PdmpConstants c = make_pdmp_constants(m, s);
        e.constants = c;
        r.stop_rule = "exact";
        r.lattice_bound = c.n_max * c.delta;
        r.lattice_step = c.delta;
        r.lattice_offset = c.x_offset;
        r.lattice_points = 2 * c.n_max + 1;
        r.truncated_mass = std::erfc(r.lattice_bound * std::sqrt(p.tau) / std::sqrt(2.0));
        r.jump_rate = c.rate;
    } else if (s.scheme == Scheme::Event) {
        // The pieces' laws live in `storage` (release_storage clears the pointer).
        std::shared_ptr<const std::vector<EventDriftPiece>> pieces;
        const EventConstants c = make_event_constants(m, s, &pieces, stop);
        e.constants = c;
        e.storage = pieces;
        r.stop_rule = c.white ? "velocity-levels" : "exact";
        if (c.white) r.white_level = c.level;
    } else {
        const ResolventConstants c = make_resolvent_constants(m, s);
        e.constants = c;
        if (c.white) {
            r.stop_rule = "velocity-levels";
            r.white_level = c.level;
        } else {
            r.stop_rule = to_string(c.rule);
        }
    }
    if (p.has_drift_law()) {
        const DriftLawReport& law = m.law_report;
        e.notes.push_back(drift_law_note(law) +
                          (given.scheme == Scheme::Auto && s.engine == Engine::Inclusion && p.white()
                               ? "; the inclusion engine runs the resolvent scheme (the white-noise event scheme "
                                 "takes the affine law only)"
                               : ""));
        e.notes.insert(e.notes.end(), law.notes.begin(), law.notes.end());
    }
    if (!p.white()) {
        r.upper_threshold = m.upper_threshold();
        r.lower_threshold = m.lower_threshold();
    }
    return e;
}

ResolvedEngine resolve_engine(const ModelParams& p, const EngineSettings& s) { return prepare_engine(p, s).resolved; }

bool PreparedEngine::release_storage() {
    if (!storage) return false;
    // Only the event scheme's constants point into storage (prepare_engine).
    if (auto* c = std::get_if<EventConstants>(&constants)) c->pieces = nullptr;
    storage.reset();
    model.law.reset(); // 16 KiB a point of a sweep; an engine that cannot run needs no law
    return true;
}

PreparedEngine prepare(const RunSettings& r) {
    PreparedEngine e = prepare_engine(r.params, r.engine, r.control.stop);
    normal_quantile_two_sided(r.level); // validates the level
    check_run_control(r.control);
    detail::check_step(e, e.notes);
    return e;
}

void validate(const RunSettings& r) { prepare(r); }

void validate(const ExcursionSettings& e) {
    if (e.excursions < 2)
        throw InvalidParameter("excursions", "excursions must be >= 2 (got " + std::to_string(e.excursions) + ")");
}

} // namespace stickslip
