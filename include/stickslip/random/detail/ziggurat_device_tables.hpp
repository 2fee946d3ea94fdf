// SPDX-License-Identifier: BSD-3-Clause
// stickslip/random/detail/ziggurat_device_tables.hpp -- the ziggurat's tables as
// device data, for CUDA builds (ziggurat.hpp includes it under __CUDACC__).
//
// Device code cannot index a host constexpr array, so each table gets a
// __device__ copy made from the host array at compile time (an element-wise
// constexpr copy: the same bits by construction, no second list of numbers to
// keep in step). The copies are const, hence of internal linkage: each CUDA
// translation unit holds its own 12 KB, and no relocatable device code is
// needed. They live in global memory and are read through the read-only data
// cache; __constant__ memory would serialise the divergent lookups of a warp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>

#include "stickslip/random/detail/exponential_ziggurat_tables.hpp"
#include "stickslip/random/detail/ziggurat_tables.hpp"

namespace stickslip::detail {

/// A table by value (an array member, so that a constexpr function can return it).
template <class T, std::size_t N>
struct ZigguratTable {
    T v[N];
};

/// The table a, element by element, at compile time.
template <class T, std::size_t N, std::size_t... I>
constexpr ZigguratTable<T, N> ziggurat_table_copy(const T (&a)[N], std::index_sequence<I...>) {
    return {{a[I]...}};
}

/// ziggurat_table_copy of every element of a.
template <class T, std::size_t N>
constexpr ZigguratTable<T, N> ziggurat_table_copy(const T (&a)[N]) {
    return ziggurat_table_copy(a, std::make_index_sequence<N>{});
}

#if defined(__CUDACC__)
__device__ const ZigguratTable<std::uint64_t, 256> zig_k_device = ziggurat_table_copy(zig_k);
__device__ const ZigguratTable<double, 256> zig_w_device = ziggurat_table_copy(zig_w);
__device__ const ZigguratTable<double, 256> zig_f_device = ziggurat_table_copy(zig_f);
__device__ const ZigguratTable<std::uint64_t, 256> zige_k_device = ziggurat_table_copy(zige_k);
__device__ const ZigguratTable<double, 256> zige_w_device = ziggurat_table_copy(zige_w);
__device__ const ZigguratTable<double, 256> zige_f_device = ziggurat_table_copy(zige_f);
#endif

} // namespace stickslip::detail
