#include "signals.h"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <mutex>
#include <utility>
#include <chrono>
#include <thread>

namespace pdd::cli {
namespace {

std::atomic<int> received{0};
std::atomic<bool> writing{false};
std::mutex cleanup_mutex;
std::function<void()> cleanup;

sigset_t cancel_signals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}

void watch() {
  const sigset_t set = cancel_signals();
  int signal = 0;
  while (sigwait(&set, &signal) != 0) {
  }
  received = signal;
  // The run stops at its next stage; a stage that takes longer is not waited for.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (writing) return;
  {
    const std::lock_guard<std::mutex> lock(cleanup_mutex);
    if (cleanup) cleanup();
  }
  static const char message[] = "pdd: interrupted\n";
  [[maybe_unused]] const auto ignored = ::write(STDERR_FILENO, message, sizeof message - 1);
  ::_exit(cancel_exit_code());
}

}  // namespace

void start_signal_watcher(char** argv, bool restart) {
  const sigset_t set = cancel_signals();
  sigset_t current;
  pthread_sigmask(SIG_BLOCK, nullptr, &current);
  if (restart || !sigismember(&current, SIGINT) || !sigismember(&current, SIGTERM)) {
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
    // OpenBLAS starts its threads when it is loaded, before main, with the
    // signals open; a thread inherits the mask only from its creator, so the
    // process starts over with the mask already set. Should exec fail, the run
    // goes on, and a signal may end it the default way.
    ::execv("/proc/self/exe", argv);
  }
  std::thread(watch).detach();
}

bool cancel_requested() { return received != 0; }

int cancel_exit_code() { return 128 + received; }

void begin_outputs() { writing = true; }

void on_interrupt(std::function<void()> action) {
  const std::lock_guard<std::mutex> lock(cleanup_mutex);
  cleanup = std::move(action);
}

}  // namespace pdd::cli
