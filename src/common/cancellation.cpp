#include "common/cancellation.h"

#include <chrono>
#include <utility>

namespace pdd::detail {
namespace {

thread_local PollScope* innermost = nullptr;

double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

PollScope::PollScope(std::function<bool()> ask, double interval_seconds)
    : ask_(std::move(ask)), interval_(interval_seconds), last_(now_seconds()), outer_(innermost) {
  if (ask_) innermost = this;
}

PollScope::~PollScope() {
  if (innermost == this) innermost = outer_;
}

void poll() {
  PollScope* scope = innermost;
  if (!scope) return;
  const double now = now_seconds();
  if (now - scope->last_ < scope->interval_) return;
  scope->last_ = now;
  if (!scope->ask_()) throw Cancelled{};
}

}  // namespace pdd::detail
