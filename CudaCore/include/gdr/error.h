// One error policy for the whole engine (see README "Errors"):
// device code sets status words, host code throws gdr::Error, the facade returns a Status.
#pragma once
#include <stdexcept>
#include <string>

namespace gdr {

enum class Status {
  Ok = 0,
  InvalidInput,           // malformed or out-of-range input or parameters
  SelfIntersectingInput,  // crossing / overlapping segments, self-intersecting surfaces
  OutOfDeviceMemory,      // a device (or host) allocation failed
  NoDevice,               // GPU backend requested but no usable CUDA device
  Aborted,                // the caller's abort callback asked to stop
  IoError,                // file missing, unreadable or malformed
  InternalError           // a bug: an invariant of the engine did not hold
};

const char* to_string(Status s);

// The one exception type of the core. Filters and the CLI catch it at their boundary.
class Error : public std::runtime_error {
 public:
  Error(Status status, const std::string& message)
      : std::runtime_error(message), status_(status) {}
  Status status() const { return status_; }

 private:
  Status status_;
};

}  // namespace gdr
