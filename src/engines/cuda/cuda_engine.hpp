// SPDX-License-Identifier: BSD-3-Clause
// Internal: the CUDA backend's host interface (src/engines/cuda/long_excursions.cu).
//
// Built only with the CMake option STICKSLIP_CUDA (target stickslip_cuda).
// Every call runs on the current CUDA device of the calling thread and
// blocks until its results are on the host. Errors (no device, a failed
// launch, out of memory) are thrown as std::runtime_error with CUDA's message.
#pragma once

#include <cstdint>
#include <string>

#include "stickslip/kernels/event_scheme.hpp"
#include "stickslip/excursion.hpp"
#include "stickslip/kernels/resolvent.hpp"

namespace stickslip::cuda {

/// The CUDA device this process would use, if any.
struct DeviceInfo {
    bool present = false; ///< a device is usable (driver and device found)
    std::string name;     ///< e.g. "NVIDIA H200"; empty without a device
    int major = 0, minor = 0; ///< compute capability
    int multiprocessors = 0;
    double memory_gib = 0.0;
    std::string error;    ///< why there is none (CUDA's message), when !present
};

/// Looks for a device; never throws.
DeviceInfo device_info();

/// What the kernels were compiled with, for reports: the CUDA version and
/// the architectures (e.g. "CUDA 13.0, sm_90").
std::string build_info();

/// Timing of one call [s]: the kernel alone (CUDA events) and the whole call,
/// transfers and allocation included.
struct DeviceTiming {
    double kernel_seconds = 0.0;
    double total_seconds = 0.0;
    unsigned threads = 0; ///< device threads launched
};

/// Long excursions first .. first+count-1 of the inclusion engine (resolvent
/// scheme) on the device: out[i] is bitwise what
/// resolvent_long_excursion(c, CounterRng(seed, LongExcursion, first + i))
/// gives, up to the transcendental functions (portable_math.hpp). `threads`
/// limits the device threads (0: as many as fit on the device at once).
DeviceTiming resolvent_long_excursions(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first,
                                       std::uint64_t count, ExcursionOutcome* out, unsigned threads = 0);

/// The same for the event scheme (streams LongExcursion and Refinement).
DeviceTiming event_long_excursions(const EventConstants& c, std::uint64_t seed, std::uint64_t first,
                                   std::uint64_t count, ExcursionOutcome* out, unsigned threads = 0);

} // namespace stickslip::cuda
