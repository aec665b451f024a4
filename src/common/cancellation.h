// Private to src/: cancellation inside a stage. While a PollScope lives, the
// long loops of its thread (CG iterations, insertions, per-level setups) call
// poll(), which asks the run's progress callback again at most every
// `interval` seconds and throws Cancelled when it answers false, so that a
// run stops within a fraction of a second whatever stage it is in.
#pragma once

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

}  // namespace pdd::detail
