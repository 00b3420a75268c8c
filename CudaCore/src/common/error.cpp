#include "gdr/error.h"

namespace gdr {

const char* to_string(Status s) {
  switch (s) {
    case Status::Ok: return "Ok";
    case Status::InvalidInput: return "InvalidInput";
    case Status::SelfIntersectingInput: return "SelfIntersectingInput";
    case Status::OutOfDeviceMemory: return "OutOfDeviceMemory";
    case Status::NoDevice: return "NoDevice";
    case Status::Aborted: return "Aborted";
    case Status::IoError: return "IoError";
    case Status::InternalError: return "InternalError";
  }
  return "Unknown";
}

}  // namespace gdr
