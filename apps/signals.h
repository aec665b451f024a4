// SIGINT and SIGTERM cancel a run of the command line at any stage, leave no
// output and exit with 130 or 143.
#pragma once

#include <functional>

namespace pdd::cli {

// Thrown by a command that stopped because of a signal; main exits with
// cancel_exit_code().
struct Interrupted {};

// Blocks SIGINT and SIGTERM in every thread of the process (call it first in
// main, with main's argv: the process re-executes itself once, so that the
// threads libraries start before main are born with them blocked too): they
// are never delivered to a handler, not even to the one METIS installs for
// SIGTERM while it orders a matrix, which once deadlocked a run. A watcher
// thread takes them with sigwait and raises the flag cancel_requested() reads.
// `restart`: re-execute even when the signals are blocked already (the
// environment changed, huge_pages.h).
void start_signal_watcher(char** argv, bool restart = false);

// True once SIGINT or SIGTERM has arrived; the exit code it asks for (130 or 143).
bool cancel_requested();
int cancel_exit_code();

// Between begin_outputs() and the end of the process the run writes its
// outputs: the watcher leaves the exit to it (it checks cancel_requested()
// before it commits them). Before that, a run that does not reach its next
// stage within two seconds of the signal is ended by the watcher itself,
// which it can do at once since nothing has been written yet.
void begin_outputs();

// What the watcher does before it ends the process on a signal (remove the
// run's staged temporaries); empty to do nothing. Set it for the life of the
// objects it touches only.
void on_interrupt(std::function<void()> cleanup);

}  // namespace pdd::cli
