// SPDX-License-Identifier: BSD-3-Clause
// The report of a run stopped before it had anything to estimate (a signal
// before the first block finished): the command line still writes a result,
// so that "one signal never loses the result" holds every time, but one that
// says plainly that there is no estimate, with no number standing in for one.
#include "report/common.hpp"
#include "stickslip/report.hpp"

namespace stickslip {

using detail::ordered_json;

namespace {

std::string what_completed(const RunInterrupted& e) {
    const std::string singular = e.samples.substr(0, e.samples.size() - 1);
    return e.completed == 0 ? "no " + singular + " completed" : "only 1 " + singular + " completed";
}

} // namespace

std::string to_json(const RunInterrupted& e, const char* command, const std::vector<std::string>& warnings,
                    int indent) {
    // "quantity" as every report has it, here saying there is none; the
    // subcommand under its own key ("command" is a command line elsewhere).
    ordered_json j;
    j["quantity"] = "interrupted";
    j["subcommand"] = command;
    j["result"] = what_completed(e);
    j["completed"] = e.completed;
    j["requested"] = e.requested;
    // No request reaches this report (the run threw before it had a result):
    // its provenance is the subcommand alone.
    detail::add_report_tail(j, ordered_json::object(), nullptr, warnings, true);
    return detail::dump(j, indent);
}

std::string to_table(const RunInterrupted& e, const char* command, const std::vector<std::string>& warnings) {
    std::ostringstream os = detail::report_stream();
    os << command << ": interrupted: " << what_completed(e);
    // requested 0: stopped while it prepared (or in a pilot run), before the
    // run proper had a size.
    if (e.requested > 0) os << " (" << e.completed << " of " << e.requested << " " << e.samples << ")";
    else os << " (stopped while preparing the run)";
    os << ", so there is no estimate\n" << detail::notes(warnings);
    return os.str();
}

std::string to_csv(const RunInterrupted& e, const char* command) {
    std::ostringstream os = detail::report_stream();
    os << "command,interrupted,completed,requested,result\n"
       << command << ",true," << e.completed << "," << e.requested << "," << what_completed(e) << "\n";
    return os.str();
}

} // namespace stickslip
