// SPDX-License-Identifier: BSD-3-Clause
// The checks of a model's numbers, apart from its drift law: validate(p)
// runs them and then makes the law to check it; make_model runs them and
// makes the law once, keeping it.
#pragma once

#include "stickslip/params.hpp"

namespace stickslip::detail {

/// validate(p) without making the drift law (InvalidParameter on the first
/// problem).
void validate_numbers(const ModelParams& p);

} // namespace stickslip::detail
