// Status and Result<T>: errors as values for everything that touches untrusted
// bytes or user input. A Status carries a code and a message a person can act on.
#ifndef MESHWAVE_STATUS_H_
#define MESHWAVE_STATUS_H_

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace meshwave {

enum class StatusCode {
  kOk = 0,
  kInvalidArgument,  // the caller asked for something impossible
  kNotFound,         // a file or an entry does not exist
  kIoError,          // the operating system refused a read or a write
  kParseError,       // input bytes are malformed (a file, a request)
  kNeedMoreInput,    // input is a valid prefix: not an error, feed more bytes
  kUnsupported,      // well-formed but outside what this version handles
  kNotSemiRegular,   // a mesh lacks subdivision connectivity
  kNotManifold,      // an operation needs a manifold mesh
  kInternal,         // a broken invariant of our own
};

const char* StatusCodeName(StatusCode code);

class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(StatusCode code, std::string message)
      : code_(code), message_(std::move(message)) {}

  static Status Ok() { return Status(); }

  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }
  // "<code name>: <message>", for logs and command-line errors.
  std::string ToString() const;

  // Returns a copy whose message is prefixed by `context: `.
  Status WithContext(const std::string& context) const;

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

inline Status InvalidArgument(std::string m) {
  return Status(StatusCode::kInvalidArgument, std::move(m));
}
inline Status ParseError(std::string m) {
  return Status(StatusCode::kParseError, std::move(m));
}
inline Status IoError(std::string m) {
  return Status(StatusCode::kIoError, std::move(m));
}

// Either a value or a non-OK Status.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : data_(std::move(value)) {}  // NOLINT: implicit by design
  Result(Status status) : data_(std::move(status)) {  // NOLINT
    assert(!std::get<Status>(data_).ok() && "Result built from an OK status");
  }

  bool ok() const { return std::holds_alternative<T>(data_); }
  const Status& status() const {
    static const Status kOkStatus;
    return ok() ? kOkStatus : std::get<Status>(data_);
  }
  T& value() & { return std::get<T>(data_); }
  const T& value() const& { return std::get<T>(data_); }
  T&& value() && { return std::get<T>(std::move(data_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

 private:
  std::variant<T, Status> data_;
};

}  // namespace meshwave

#define MW_CONCAT_INNER_(a, b) a##b
#define MW_CONCAT_(a, b) MW_CONCAT_INNER_(a, b)

// Returns the Status from the enclosing function when `expr` is not OK.
#define MW_RETURN_IF_ERROR(expr)                         \
  do {                                                   \
    ::meshwave::Status mw_status_ = (expr);              \
    if (!mw_status_.ok()) return mw_status_;             \
  } while (0)

// `lhs = value of expr`, or return its Status from the enclosing function.
#define MW_ASSIGN_OR_RETURN(lhs, expr) \
  MW_ASSIGN_OR_RETURN_IMPL_(MW_CONCAT_(mw_result_, __LINE__), lhs, expr)
#define MW_ASSIGN_OR_RETURN_IMPL_(tmp, lhs, expr) \
  auto tmp = (expr);                              \
  if (!tmp.ok()) return tmp.status();             \
  lhs = std::move(tmp).value()

#endif  // MESHWAVE_STATUS_H_
