// SPDX-License-Identifier: BSD-3-Clause
#include "distributed.hpp"

#include "stickslip/stats/exact_sum.hpp"
#include "stickslip/params.hpp"

#include <cstdlib>
#include <limits>
#include <vector>

#ifdef STICKSLIP_WITH_MPI
#include <mpi.h>
#endif

namespace stickslip::cli {

namespace {
unsigned g_rank = 0, g_ranks = 1;
bool g_started = false;

#ifdef STICKSLIP_WITH_MPI
/// Launched by mpirun (Open MPI), an MPICH/PMI launcher, or PMIx?
bool under_launcher() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
        if (std::getenv(v)) return true;
    return false;
}

/// The MPI user operation of exact sums: inout[k] += in[k] for every ExactSum
/// of the buffer (a datatype of ExactSum::words 64-bit words). Exact, so it is
/// commutative and associative: any reduction tree gives the same words.
void merge_exact_sums(void* in, void* inout, int* len, MPI_Datatype*) {
    const auto* a = static_cast<const std::uint64_t*>(in);
    auto* b = static_cast<std::uint64_t*>(inout);
    for (int k = 0; k < *len; ++k) ExactSum::merge_words(a + k * ExactSum::words, b + k * ExactSum::words);
}

/// Replaces this process's exact sums and counts by their totals over every
/// process: one all-reduce each, of a size that does not depend on the run.
void all_reduce(std::vector<std::uint64_t>& words, std::vector<std::uint64_t>& counts) {
    static MPI_Datatype chunk = [] {
        MPI_Datatype t;
        MPI_Type_contiguous(static_cast<int>(ExactSum::words), MPI_UINT64_T, &t);
        MPI_Type_commit(&t);
        return t;
    }();
    static MPI_Op op = [] {
        MPI_Op o;
        MPI_Op_create(&merge_exact_sums, 1, &o);
        return o;
    }();
    const auto chunks = static_cast<int>(words.size() / ExactSum::words);
    if (chunks > 0) MPI_Allreduce(MPI_IN_PLACE, words.data(), chunks, chunk, op, MPI_COMM_WORLD);
    if (!counts.empty())
        MPI_Allreduce(MPI_IN_PLACE, counts.data(), static_cast<int>(counts.size()), MPI_UINT64_T, MPI_SUM,
                      MPI_COMM_WORLD);
}
#endif
} // namespace

void start_distribution(int& argc, char**& argv) {
#ifdef STICKSLIP_WITH_MPI
    if (!under_launcher()) return;
    MPI_Init(&argc, &argv);
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    g_rank = static_cast<unsigned>(rank);
    g_ranks = static_cast<unsigned>(size);
    g_started = true;
#else
    (void)argc;
    (void)argv;
#endif
}

void stop_distribution() {
#ifdef STICKSLIP_WITH_MPI
    if (g_started) MPI_Finalize();
#endif
    g_started = false;
}

void abort_distribution(int code) {
#ifdef STICKSLIP_WITH_MPI
    if (g_started) MPI_Abort(MPI_COMM_WORLD, code);
#endif
    std::exit(code);
}

bool distributed() { return g_ranks > 1; }
bool is_root() { return g_rank == 0; }

bool all_ok(bool ok) {
#ifdef STICKSLIP_WITH_MPI
    if (g_ranks > 1) {
        int mine = ok ? 1 : 0, all = 0;
        MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
        return all != 0;
    }
#endif
    return ok;
}

void distribute(RunControl& control) {
#ifdef STICKSLIP_WITH_MPI
    if (g_ranks > 1) {
        control.rank = g_rank;
        control.ranks = g_ranks;
        control.reduce = all_reduce;
    }
#else
    (void)control;
#endif
}

} // namespace stickslip::cli
