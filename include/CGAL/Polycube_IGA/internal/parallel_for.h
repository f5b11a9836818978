// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A minimal parallel loop for work split by volume patch (untangling energies, Jacobian
// certificates). Each index writes only its own results and the caller combines them in
// index order afterwards, so what it computes does not depend on the number of threads:
// the package's output stays the same bit for bit on any machine.

#ifndef CGAL_POLYCUBE_IGA_INTERNAL_PARALLEL_FOR_H
#define CGAL_POLYCUBE_IGA_INTERNAL_PARALLEL_FOR_H

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

#if defined(__linux__)
#include <sched.h>
#endif

namespace CGAL {
namespace Polycube_IGA {
namespace internal {

/// The number of threads to use for `requested` (0: one per core this process may run on,
/// at least 1). On Linux the affinity mask counts, not the machine: a run pinned to one core
/// (taskset, the benchmark driver, a container's cpuset) gets one thread, not a pool that
/// takes turns on it.
inline unsigned worker_count(unsigned requested)
{
  if(requested > 0) return requested;
#if defined(__linux__)
  cpu_set_t set;
  CPU_ZERO(&set);
  if(sched_getaffinity(0, sizeof(set), &set) == 0) return unsigned(std::max(1, CPU_COUNT(&set)));
#endif
  return std::max(1u, std::thread::hardware_concurrency());
}

/// Calls f(i, worker) once for every i in [0, n), on at most `threads` threads (0: as
/// worker_count(0)); `worker` in [0, number of threads) names the calling thread, for
/// per-thread scratch space. Indices are handed out in order as threads become free. If
/// calls throw, the exception of the lowest such index is rethrown once all have ended.
template <class F>
void parallel_for(std::size_t n, unsigned threads, F&& f)
{
  const unsigned t = unsigned(std::min<std::size_t>(worker_count(threads), std::max<std::size_t>(n, 1)));
  if(t <= 1) {
    for(std::size_t i = 0; i < n; ++i) f(i, 0u);
    return;
  }
  std::atomic<std::size_t> next(0);
  std::vector<std::exception_ptr> error(n);
  auto work = [&](unsigned worker) {
    for(std::size_t i = next++; i < n; i = next++) {
      try {
        f(i, worker);
      } catch(...) {
        error[i] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for(unsigned w = 1; w < t; ++w) pool.emplace_back(work, w);
  work(0u);
  for(std::thread& th : pool) th.join();
  for(const std::exception_ptr& e : error)
    if(e) std::rethrow_exception(e);
}

} // namespace internal
} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_INTERNAL_PARALLEL_FOR_H
