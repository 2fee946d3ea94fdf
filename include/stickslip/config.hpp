// stickslip/config.hpp -- portability macros shared by every public header.
//
// The per-step and per-event kernels (inclusion.hpp, pdmp.hpp, noise.hpp,
// rng.hpp) are meant to compile unchanged for the CPU and, later, for a CUDA
// backend, in the style of HOOMD-blue's RandomNumbers.h. They therefore avoid
// allocation, exceptions and virtual calls, and are marked STICKSLIP_HD so
// that nvcc sees them as __host__ __device__ functions.
#pragma once

#if defined(__CUDACC__)
#define STICKSLIP_HD __host__ __device__
#else
#define STICKSLIP_HD
#endif

#define STICKSLIP_VERSION_MAJOR 0
#define STICKSLIP_VERSION_MINOR 1
#define STICKSLIP_VERSION_PATCH 0
#define STICKSLIP_VERSION_STRING "0.1.0"
