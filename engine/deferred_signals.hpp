// SIGINT and SIGTERM held back while a file is being put in place: a signal that arrives meanwhile is delivered when
// the guard ends, so that a stop (or a second Ctrl-C, which ends the program at once) never leaves a temporary file
// or a half-moved folder behind.
#pragma once

#include <csignal>

#include <pthread.h>

namespace fretwear {

class DeferredStopSignals {
 public:
  DeferredStopSignals() {
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop, &previous_);
  }
  ~DeferredStopSignals() { pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }
  DeferredStopSignals(const DeferredStopSignals&) = delete;
  DeferredStopSignals& operator=(const DeferredStopSignals&) = delete;

 private:
  sigset_t previous_;
};

}  // namespace fretwear
