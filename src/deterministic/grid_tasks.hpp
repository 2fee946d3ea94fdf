// SPDX-License-Identifier: BSD-3-Clause
// The grids of a round (or their spectra), solved two at a time: what both
// discretisations of the Kolmogorov engine do with their grids. Internal to
// the library.
//
// Why two. Each grid is one sequential sparse factorisation, and a round's
// memory is predicted as two of them at once whatever the thread count
// (kolmogorov.cpp), so that where a solve stops does not depend on it; each
// index is written by its own task, so neither does the result.
#pragma once

#include <atomic>
#include <cstddef>
#include <future>
#include <map>
#include <optional>
#include <vector>

namespace stickslip::detail {

/// Runs task(i) for every i in [0, n): on two threads when threads > 1 and
/// n > 1 (this one and one more), else on this one; each free thread takes
/// the next index in increasing order. `stop` (may be null) is polled before
/// each index: once it is set, no further index starts. Whether every index
/// ran. An exception of a task reaches the caller.
template <class Task>
bool run_grid_tasks(std::size_t n, int threads, const std::atomic<bool>* stop, Task&& task) {
    std::atomic<std::size_t> next{0};
    std::atomic<bool> stopped{false};
    auto work = [&] {
        for (std::size_t i; (i = next++) < n;) {
            if (stop && stop->load()) {
                stopped = true;
                return;
            }
            task(i);
        }
    };
    if (threads > 1 && n > 1) {
        std::future<void> second = std::async(std::launch::async, work);
        work();
        second.get();
    } else {
        work();
    }
    return !stopped;
}

/// The spectrum's values on each of `keys` (grids of a round), spectrum(key)
/// run for each through run_grid_tasks; std::nullopt when `stop` ended it
/// first.
template <class Key, class Spectrum>
std::optional<std::map<Key, std::vector<double>>> spectra_on_grids(const std::vector<Key>& keys, int threads,
                                                                   const std::atomic<bool>* stop, Spectrum&& spectrum) {
    std::vector<std::vector<double>> values(keys.size());
    if (!run_grid_tasks(keys.size(), threads, stop, [&](std::size_t i) { values[i] = spectrum(keys[i]); }))
        return std::nullopt;
    std::map<Key, std::vector<double>> out;
    for (std::size_t i = 0; i < keys.size(); ++i) out.emplace(keys[i], std::move(values[i]));
    return out;
}

} // namespace stickslip::detail
