// Result<T>: the value of an operation on untrusted input, or the reason it failed.
//
// Engine code never throws (em++ 3.1.6 aborts the whole module on a throw): decoders, parsers and
// loaders return a Result whose error message names what failed and where (file, section, byte
// offset or line). Programmer errors are asserts, not Results.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace qv {

/// A failure description meant for a person: "tile 3/2/1.qvt: section VERT at byte 40: ...".
struct Error {
  std::string message;
};

template <typename T>
class Result {
 public:
  Result(T value) : state_(std::move(value)) {}      // NOLINT(google-explicit-constructor)
  Result(Error error) : state_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  [[nodiscard]] bool ok() const { return state_.index() == 0; }
  explicit operator bool() const { return ok(); }

  /// Precondition: ok().
  T& value() & { return std::get<0>(state_); }
  const T& value() const& { return std::get<0>(state_); }
  T&& value() && { return std::get<0>(std::move(state_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

  /// Precondition: !ok().
  const std::string& error() const { return std::get<1>(state_).message; }

 private:
  std::variant<T, Error> state_;
};

/// Result of an operation that yields nothing but success or an error.
class Status {
 public:
  Status() = default;
  Status(Error error) : message_(std::move(error.message)), ok_(false) {}  // NOLINT
  [[nodiscard]] bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const std::string& error() const { return message_; }

 private:
  std::string message_;
  bool ok_ = true;
};

/// Convenience: `return fail("bad thing at ", offset);` builds an Error from streamable parts.
Error fail(std::string message);

}  // namespace qv
