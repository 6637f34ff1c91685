// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#ifndef ANISO_CONFORMAL_INTERNAL_PARALLEL_FOR_H
#define ANISO_CONFORMAL_INTERNAL_PARALLEL_FOR_H

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

// The per-element loops of the metric, the dual mesh and the quality on several threads
// (`number_of_threads`, 0 = every core). Each thread takes one contiguous block of the index range, so a
// body that writes only the outputs of its own index gives results that do not depend on the number of
// threads; reductions (sums, extremes, histograms) are left to the caller, in index order, after the loop.
// Plain std::thread: the loops are uniform, run once per stage, and start in tens of microseconds, so
// neither a pool nor work stealing (TBB) would pay for a new dependency.

namespace Aniso_conformal {
namespace internal {

// the number of threads meant by `requested` (0: every core)
inline unsigned resolve_thread_count(unsigned requested)
{
  return requested ? requested : std::max(1u, std::thread::hardware_concurrency());
}

/*
 * Calls block(begin, end, t) for consecutive blocks [begin, end) covering [0, n), block t of at most
 * `threads` (0: every core), each of at least `grain` indices (fewer blocks for short ranges, one below 2
 * grains), block 0 on the calling thread. A block may keep its own scratch state. An exception thrown by a
 * block is rethrown here after every thread has stopped (the one of the first block that threw).
 */
template <typename Block>
void parallel_blocks(std::size_t n, unsigned threads, const Block& block, std::size_t grain = 2048)
{
  const std::size_t most = std::max<std::size_t>(1, n / std::max<std::size_t>(1, grain));
  const std::size_t nt = std::min<std::size_t>(resolve_thread_count(threads), most);
  if(nt <= 1) {
    block(std::size_t(0), n, std::size_t(0));
    return;
  }
  std::vector<std::exception_ptr> errors(nt);
  auto run = [&](std::size_t t) {
    try {
      block(n * t / nt, n * (t + 1) / nt, t);
    } catch(...) {
      errors[t] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(nt - 1);
  std::size_t started = 1;
  try {
    for(; started < nt; ++started) pool.emplace_back(run, started);
  } catch(const std::system_error&) {  // no more threads to be had: this one does the rest
  }
  for(std::size_t t = started; t < nt; ++t) run(t);
  run(0);
  for(auto& th : pool) th.join();
  for(const auto& e : errors)
    if(e) std::rethrow_exception(e);
}

// calls body(i) for every i in [0, n) as parallel_blocks() does
template <typename Body>
void parallel_for(std::size_t n, unsigned threads, const Body& body, std::size_t grain = 2048)
{
  parallel_blocks(
      n, threads,
      [&body](std::size_t begin, std::size_t end, std::size_t) {
        for(std::size_t i = begin; i < end; ++i) body(i);
      },
      grain);
}

// calls body(order[k]) for every k in [0, order.size()) on up to `threads` threads (0: every core), each
// thread taking the next k not yet taken: for bodies of very unequal cost (put the costliest first). As
// with parallel_blocks(), a body that writes only the outputs of its own index gives results that do not
// depend on the number of threads; an exception is rethrown here after every thread has stopped.
template <typename Body>
void parallel_for_dynamic(const std::vector<std::size_t>& order, unsigned threads, const Body& body)
{
  const std::size_t n = order.size();
  const std::size_t nt = std::min<std::size_t>(resolve_thread_count(threads), n);
  std::atomic<std::size_t> next{0};
  parallel_blocks(
      nt, unsigned(nt),
      [&](std::size_t, std::size_t, std::size_t) {
        for(std::size_t k = next++; k < n; k = next++) body(order[k]);
      },
      1);
}

} // namespace internal
} // namespace Aniso_conformal

#endif // ANISO_CONFORMAL_INTERNAL_PARALLEL_FOR_H
