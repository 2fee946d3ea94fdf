// SPDX-License-Identifier: BSD-3-Clause
// stickslip/version.hpp -- which stickslip this is: the release version and,
// when the library was built from a git checkout, the source revision. Every
// JSON report names both, `stickslip --version` prints both and a checkpoint
// records both, so a result can be traced to the code that made it.
#pragma once

/// \file
/// The library's release version and source revision. The comment at the top of
/// this header explains the design.

namespace stickslip {

/// The release version, "MAJOR.MINOR.PATCH" (STICKSLIP_VERSION_STRING).
const char* version();

/// The source revision the library was built from: the commit (12 hex digits)
/// followed by "-dirty" when the checkout had uncommitted changes; "" when the
/// build did not come from a git checkout (a source archive, an sdist).
const char* source_revision();

/// Both on one line, "stickslip 0.1.0 (git 0123456789ab)", or "(git unknown)"
/// without a revision: what `stickslip --version` prints and what a checkpoint
/// must match to be resumed.
const char* version_line();

} // namespace stickslip
