// Private to src/: cancellation inside a stage. While a PollScope lives, the
// long loops of its thread (CG iterations, insertions, per-level setups) call
// poll(), which asks the run's progress callback again at most every
// `interval` seconds and throws Cancelled when it answers false, so that a
// run stops inside whatever stage it is in (how soon: docs/benchmarks.md,
// "Cancellation inside a stage").
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <functional>

namespace pdd::detail {

// Thrown by poll() (and the run's reports) when the callback asks to stop;
// caught where the run started.
struct Cancelled {};

class PollScope {
 public:
  // `ask` returns false to stop; an empty `ask` installs nothing. Scopes nest
  // (the normals' coarse run inside a run): the innermost one is asked.
  PollScope(std::function<bool()> ask, double interval_seconds);
  ~PollScope();
  PollScope(const PollScope&) = delete;
  PollScope& operator=(const PollScope&) = delete;

 private:
  friend void poll();
  std::function<bool()> ask_;
  double interval_;
  double last_ = 0;  // seconds on the steady clock of the last ask
  PollScope* outer_;
};

// Cheap when no scope is installed on this thread or the interval has not
// passed; call only where an exception may leave (not inside a parallel loop).
void poll();

// For a serial loop over a million items: poll() once every `period` of them
// (a power of two; fewer where each item costs microseconds).
inline void poll_every(std::size_t i, std::size_t period = std::size_t(1) << 16) {
  if ((i & (period - 1)) == period - 1) poll();
}

// body(range) over [0, n) in parallel (tbb::blocked_range<Index>), a slice of
// `slice` items at a time with poll() between slices: for the loops that take
// seconds at a million items.
template <class Index, class RangeBody>
void polled_parallel_ranges(Index n, const RangeBody& body, Index slice = Index(1) << 15) {
  for (Index begin = 0; begin < n; begin += slice) {
    const Index end = std::min(n, begin + slice);
    tbb::parallel_for(tbb::blocked_range<Index>(begin, end), body);
    poll();
  }
}

// body(i) for i in [0, n), the same way.
template <class Index, class Body>
void polled_parallel_for(Index n, const Body& body, Index slice = Index(1) << 15) {
  polled_parallel_ranges(
      n,
      [&](const tbb::blocked_range<Index>& r) {
        for (Index i = r.begin(); i != r.end(); ++i) body(i);
      },
      slice);
}

}  // namespace pdd::detail
