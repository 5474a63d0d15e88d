// The library's threads: loops over vertices split into one contiguous chunk per thread, on
// a pool of standard threads kept for the life of the process. The same in every build (no
// OpenMP runtime to ship), and results do not depend on the thread count: each iteration
// writes only its own outputs, and the reductions are order-free (max, or).
#pragma once

#include <algorithm>
#include <functional>

namespace geofair {

/// Loops over fewer vertices than this run on one thread: below it waking the pool's threads
/// costs more than they save (docs/DESIGN_NOTES.md).
constexpr int kParallelMin = 150;

/// The threads parallel loops started on this thread may use (at least 1; by default the
/// cores of the machine). fair() sets it for its solve (fairing.cpp, solve_threads).
int loop_threads();
void set_loop_threads(int threads);

/// The threads of one solve (fair, a LiveFairing frame): GEOFAIR_NUM_THREADS where it is
/// set (an exact request), else max_threads() less the cores that other processes keep
/// busy now (fairing.cpp).
int solve_threads();

/// The environment's GEOFAIR_NUM_THREADS as a positive count (read once, at most 4 threads a
/// core), else 0.
int requested_threads_from_environment();

/// The cores of the machine (at least 1).
int machine_cores();

/// The most threads a solve uses: the environment's GEOFAIR_NUM_THREADS, else
/// OMP_NUM_THREADS (the convention OpenBLAS also follows), else the machine's cores.
int max_threads();

/// Runs chunk(t, begin, end) for the contiguous chunks [begin, end) of [0, n), one per
/// thread t in [0, T), T = loop_threads() when `parallel` and n > 1, else 1 (one call on
/// this thread, t = 0). Chunk t of T is [n t / T, n (t+1) / T). Waits for all; an exception
/// of a chunk is rethrown here. While the pool serves another loop (a concurrent solve, or
/// a loop started inside a chunk) the loop runs on this thread alone.
void parallel_chunks(int n, bool parallel, const std::function<void(int, int, int)>& chunk);

/// parallel_chunks calling body(i) for each i of its chunk.
template <class Body>
void parallel_for(int n, bool parallel, Body&& body) {
  parallel_chunks(n, parallel, [&](int, int begin, int end) {
    for (int i = begin; i < end; ++i) body(i);
  });
}

}  // namespace geofair
