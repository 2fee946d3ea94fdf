// stickslip/report.hpp -- machine- and human-readable reports of results.
//
// The JSON schema is a contract that users script against (documented in
// README.md, section "JSON output"); the Python module's to_dict() is the same object. Infinite
// relaxation is written as the string "inf". Timing lives under "work" so that
// results can be compared with it removed.
#pragma once

#include <string>

#include "diffusivity.hpp"

namespace stickslip {

/// One JSON object (pretty-printed with `indent` spaces; -1 for one line).
std::string to_json(const DiffusivityResult& r, int indent = 2);
std::string to_json(const BruteForceResult& r, int indent = 2);

/// Small aligned table with units, physical and nondimensional.
std::string to_table(const DiffusivityResult& r);
std::string to_table(const BruteForceResult& r);

} // namespace stickslip
