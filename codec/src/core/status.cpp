#include "meshwave/status.h"

namespace meshwave {

const char* StatusCodeName(StatusCode code) {
  switch (code) {
    case StatusCode::kOk: return "ok";
    case StatusCode::kInvalidArgument: return "invalid argument";
    case StatusCode::kNotFound: return "not found";
    case StatusCode::kIoError: return "i/o error";
    case StatusCode::kParseError: return "parse error";
    case StatusCode::kNeedMoreInput: return "need more input";
    case StatusCode::kUnsupported: return "unsupported";
    case StatusCode::kNotSemiRegular: return "not semi-regular";
    case StatusCode::kNotManifold: return "not manifold";
    case StatusCode::kInternal: return "internal error";
    case StatusCode::kStale: return "stale";
  }
  return "unknown";
}

std::string Status::ToString() const {
  if (ok()) return "ok";
  return std::string(StatusCodeName(code_)) + ": " + message_;
}

Status Status::WithContext(const std::string& context) const {
  if (ok()) return *this;
  return Status(code_, context + ": " + message_);
}

}  // namespace meshwave
