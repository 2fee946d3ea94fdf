#include "distributed.hpp"

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

constexpr int kRecordDoubles = 3 + BivariateMoments::raw_size;

/// All-gathers every process's block records (block, capped, work, raw moments).
std::vector<BlockRecord> all_gather(std::vector<BlockRecord> mine) {
    std::vector<double> send(mine.size() * kRecordDoubles);
    for (std::size_t k = 0; k < mine.size(); ++k) {
        double* p = &send[k * kRecordDoubles];
        p[0] = static_cast<double>(mine[k].block); // block numbers < 2^50: exact
        p[1] = static_cast<double>(mine[k].capped);
        p[2] = static_cast<double>(mine[k].work);
        mine[k].moments.to_raw(p + 3);
    }
    // MPI counts are ints: refuse (on every process alike) rather than overflow.
    const bool fits = send.size() * g_ranks < static_cast<std::size_t>(std::numeric_limits<int>::max());
    if (!all_ok(fits))
        throw InvalidParameter("excursions", "too many sample blocks to gather across processes; use fewer "
                                             "excursions per run");
    int count = static_cast<int>(send.size());
    std::vector<int> counts(g_ranks), offsets(g_ranks, 0);
    MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    for (unsigned r = 1; r < g_ranks; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
    std::vector<double> recv(static_cast<std::size_t>(offsets.back() + counts.back()));
    MPI_Allgatherv(send.data(), count, MPI_DOUBLE, recv.data(), counts.data(), offsets.data(), MPI_DOUBLE,
                   MPI_COMM_WORLD);
    std::vector<BlockRecord> all(recv.size() / kRecordDoubles);
    for (std::size_t k = 0; k < all.size(); ++k) {
        const double* p = &recv[k * kRecordDoubles];
        all[k].block = static_cast<std::uint64_t>(p[0]);
        all[k].capped = static_cast<std::uint64_t>(p[1]);
        all[k].work = static_cast<std::uint64_t>(p[2]);
        all[k].moments = BivariateMoments::from_raw(p + 3);
    }
    return all;
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
        control.combine = all_gather;
    }
#else
    (void)control;
#endif
}

} // namespace stickslip::cli
