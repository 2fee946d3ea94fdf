// SPDX-License-Identifier: BSD-3-Clause
// The CUDA backend: long excursions of the inclusion engine, one per device
// thread at a time, from the same header kernels as the CPU engine.
//
// The per-thread loop is device_resolvent_worker / device_event_worker
// (stickslip/kernels/device_excursions.hpp), the code the gpu-host tests run on the
// host; this file only launches it and moves the outcomes. The kernels take
// the index of their next excursion from a counter in device memory (one
// atomic add per excursion, whose length is tens of thousands of steps), and
// write each outcome to its index, so the results cannot depend on the grid,
// on timing or on the order of the excursions.
//
// Arithmetic: compiled with -fmad=false (no contraction into fused
// multiply-adds, as -ffp-contract=off on the CPU), -prec-div=true,
// -prec-sqrt=true and -ftz=false (IEEE division, square root and subnormals,
// nvcc's defaults, made explicit so that a stray --use_fast_math cannot slip
// in): the kernels' +, -, *, / and sqrt are then the CPU's, bit for bit. Their
// exp, log and log1p are the project's own on the device (portable_math.hpp);
// the ziggurat's tables are device copies of the host's
// (detail/ziggurat_device_tables.hpp).
#include "engines/cuda/cuda_engine.hpp"

#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "stickslip/kernels/device_excursions.hpp"

namespace stickslip::cuda {

namespace {

void check(cudaError_t e, const char* what) {
    if (e != cudaSuccess) throw std::runtime_error(std::string("CUDA: ") + what + ": " + cudaGetErrorString(e));
}

/// The shared counter's next value: the index of a thread's next excursion.
struct DeviceNext {
    unsigned long long* counter;
    __device__ std::uint64_t operator()() const { return atomicAdd(counter, 1ull); }
};

template <StepKind K>
__global__ void resolvent_kernel(ResolventConstants c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                                 unsigned long long* counter, ExcursionOutcome* out) {
    DeviceNext next{counter};
    device_resolvent_worker<K>(c, seed, first, count, next, out);
}

__global__ void event_kernel(const EventConstants* c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                             unsigned long long* counter, ExcursionOutcome* out) {
    DeviceNext next{counter};
    device_event_worker(*c, seed, first, count, next, out);
}

/// Device memory, freed on scope exit.
template <class T>
struct DeviceBuffer {
    T* p = nullptr;
    explicit DeviceBuffer(std::size_t n) { check(cudaMalloc(reinterpret_cast<void**>(&p), n * sizeof(T)), "cudaMalloc"); }
    ~DeviceBuffer() { cudaFree(p); }
    DeviceBuffer(const DeviceBuffer&) = delete;
    DeviceBuffer& operator=(const DeviceBuffer&) = delete;
};

/// Blocks of `block` threads: as many as fit on the device at once (at
/// most `limit` threads when limit > 0), and no more than the excursions need.
template <class Kernel>
unsigned grid_for(Kernel kernel, int block, std::uint64_t count, unsigned limit) {
    int device = 0, sms = 0, per_sm = 0;
    check(cudaGetDevice(&device), "cudaGetDevice");
    check(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, device), "cudaDeviceGetAttribute");
    check(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm, kernel, block, 0),
          "cudaOccupancyMaxActiveBlocksPerMultiprocessor");
    std::uint64_t blocks = static_cast<std::uint64_t>(sms) * static_cast<std::uint64_t>(per_sm > 0 ? per_sm : 1);
    if (limit > 0) blocks = std::min<std::uint64_t>(blocks, (limit + block - 1) / block);
    blocks = std::min<std::uint64_t>(blocks, (count + block - 1) / block);
    return static_cast<unsigned>(blocks > 0 ? blocks : 1);
}

/// Runs launch(grid, block, counter, out) for `count` excursions and copies
/// the outcomes to host_out.
template <class Kernel, class Launch>
DeviceTiming run(Kernel kernel, std::uint64_t count, ExcursionOutcome* host_out, unsigned limit, Launch launch) {
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    DeviceTiming t;
    if (count == 0) return t;
    constexpr int block = 128;
    const unsigned grid = grid_for(kernel, block, count, limit);
    t.threads = grid * static_cast<unsigned>(block);
    DeviceBuffer<ExcursionOutcome> out(count);
    DeviceBuffer<unsigned long long> counter(1);
    check(cudaMemset(counter.p, 0, sizeof(unsigned long long)), "cudaMemset");
    cudaEvent_t e0, e1;
    check(cudaEventCreate(&e0), "cudaEventCreate");
    check(cudaEventCreate(&e1), "cudaEventCreate");
    check(cudaEventRecord(e0), "cudaEventRecord");
    launch(grid, block, counter.p, out.p);
    check(cudaGetLastError(), "kernel launch");
    check(cudaEventRecord(e1), "cudaEventRecord");
    check(cudaEventSynchronize(e1), "kernel");
    float ms = 0.0f;
    check(cudaEventElapsedTime(&ms, e0, e1), "cudaEventElapsedTime");
    cudaEventDestroy(e0);
    cudaEventDestroy(e1);
    check(cudaMemcpy(host_out, out.p, count * sizeof(ExcursionOutcome), cudaMemcpyDeviceToHost), "cudaMemcpy");
    t.kernel_seconds = ms * 1e-3;
    t.total_seconds = std::chrono::duration<double>(clock::now() - start).count();
    return t;
}

} // namespace

DeviceInfo device_info() {
    DeviceInfo d;
    int n = 0;
    const cudaError_t e = cudaGetDeviceCount(&n);
    if (e != cudaSuccess || n == 0) {
        d.error = e != cudaSuccess ? cudaGetErrorString(e) : "no CUDA device";
        cudaGetLastError(); // clear it
        return d;
    }
    int device = 0;
    cudaDeviceProp p{};
    if (cudaGetDevice(&device) != cudaSuccess || cudaGetDeviceProperties(&p, device) != cudaSuccess) {
        d.error = cudaGetErrorString(cudaGetLastError());
        return d;
    }
    d.present = true;
    d.name = p.name;
    d.major = p.major;
    d.minor = p.minor;
    d.multiprocessors = p.multiProcessorCount;
    d.memory_gib = static_cast<double>(p.totalGlobalMem) / (1024.0 * 1024.0 * 1024.0);
    return d;
}

std::string build_info() {
    return "CUDA " + std::to_string(CUDART_VERSION / 1000) + "." + std::to_string(CUDART_VERSION % 1000 / 10) +
           ", " STICKSLIP_CUDA_ARCHITECTURES_TEXT;
}

namespace {
template <StepKind K>
DeviceTiming run_resolvent(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first, std::uint64_t count,
                           ExcursionOutcome* out, unsigned threads) {
    return run(resolvent_kernel<K>, count, out, threads,
               [&](unsigned grid, int block, unsigned long long* counter, ExcursionOutcome* dev_out) {
                   resolvent_kernel<K><<<grid, block>>>(c, seed, first, count, counter, dev_out);
               });
}
} // namespace

DeviceTiming resolvent_long_excursions(const ResolventConstants& c, std::uint64_t seed, std::uint64_t first,
                                       std::uint64_t count, ExcursionOutcome* out, unsigned threads) {
    // One kernel per step kind (as with_step_kind chooses it), so that none
    // carries the registers of the others.
    if (c.white) return run_resolvent<StepKind::White>(c, seed, first, count, out, threads);
    if (c.rule == StopRule::Bridge) return run_resolvent<StepKind::ColoredBridge>(c, seed, first, count, out, threads);
    return run_resolvent<StepKind::ColoredStuck>(c, seed, first, count, out, threads);
}

DeviceTiming event_long_excursions(const EventConstants& c, std::uint64_t seed, std::uint64_t first,
                                   std::uint64_t count, ExcursionOutcome* out, unsigned threads) {
    // The constants (about 10 KB: the laws of every refinement depth) go to
    // device memory once; every thread reads the same entries (cached). A
    // knots drift law's laws per piece live in host memory (c.pieces).
    if (c.pieces)
        throw std::invalid_argument("the device's event kernel takes the affine drift law only (a knots law's laws "
                                    "per piece are in host memory)");
    DeviceBuffer<EventConstants> dc(1);
    check(cudaMemcpy(dc.p, &c, sizeof c, cudaMemcpyHostToDevice), "cudaMemcpy");
    return run(event_kernel, count, out, threads,
               [&](unsigned grid, int block, unsigned long long* counter, ExcursionOutcome* dev_out) {
                   event_kernel<<<grid, block>>>(dc.p, seed, first, count, counter, dev_out);
               });
}

} // namespace stickslip::cuda
