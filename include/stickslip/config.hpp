// SPDX-License-Identifier: BSD-3-Clause
// stickslip/config.hpp -- portability macros shared by every public header.
//
// The per-step and per-event kernels (resolvent.hpp, pdmp.hpp, noise.hpp,
// rng.hpp) are meant to compile unchanged for the CPU and, later, for a CUDA
// backend, in the style of HOOMD-blue's RandomNumbers.h. They therefore avoid
// allocation, exceptions and virtual calls, and are marked STICKSLIP_HD so
// that nvcc sees them as __host__ __device__ functions.
#pragma once

/// \file
/// Portability and version macros, included by every public header.

/// Marks a kernel callable from both host and device code: `__host__
/// __device__` under nvcc (__CUDACC__), nothing otherwise. Such functions
/// allocate nothing, throw nothing and make no virtual calls.
#if defined(__CUDACC__)
#define STICKSLIP_HD __host__ __device__
#else
#define STICKSLIP_HD
#endif

/// Release version of these headers, major part; kept equal by hand to the
/// CMake project's VERSION. stickslip::version() gives the compiled library's.
#define STICKSLIP_VERSION_MAJOR 0
/// Release version, minor part: releases with the same major and minor
/// versions are compatible (the CMake package's SameMinorVersion).
#define STICKSLIP_VERSION_MINOR 1
/// Release version, patch part.
#define STICKSLIP_VERSION_PATCH 0
/// Release version as text, "MAJOR.MINOR.PATCH".
#define STICKSLIP_VERSION_STRING "0.1.0"
