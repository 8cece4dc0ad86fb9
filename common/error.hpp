// The one root of the errors a user can cause (a scene, a file, a solve that does not converge), for contact/,
// wear/ and engine/ alike: a header of its own, so that wear/ throws them without knowing contact/. Programming
// mistakes are assert()s.
#pragma once

#include <stdexcept>
#include <string>

namespace fretwear {

// Base of every exception fretwear throws on purpose; its message says what is wrong and what to do.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Invalid input: a scene, a profile, an option. The command line maps it to exit status 2.
class InputError : public Error {
 public:
  using Error::Error;
};

// A solver stopped short of its tolerance. The command line maps it to exit status 3.
class ConvergenceError : public Error {
 public:
  using Error::Error;
};

// A stop asked for while the run computes (Ctrl-C, SIGTERM, Python's KeyboardInterrupt) outside the wear stage,
// which stops at a step boundary and keeps what it reached; here the run ends with nothing of it kept. The command
// line exits with 128 + the signal's number.
class StopRequested : public Error {
 public:
  using Error::Error;
};

// A scene asks for something fretwear cannot compute yet (a route or regime not built). Exit status 2.
class UnsupportedError : public InputError {
 public:
  using InputError::InputError;
};

}  // namespace fretwear
