#pragma once
// Expected failures as values: a Result holds a value or the reason there is none.

#include <optional>
#include <string>
#include <utility>

namespace mrslam {

template <class T>
class Result {
 public:
  static Result success(T value) { return Result(std::move(value), {}); }
  static Result failure(std::string reason) { return Result(std::nullopt, std::move(reason)); }

  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }
  const T& value() const { return *value_; }
  T& value() { return *value_; }
  /// Why there is no value (empty when ok()).
  const std::string& reason() const { return reason_; }

 private:
  Result(std::optional<T> value, std::string reason)
      : value_(std::move(value)), reason_(std::move(reason)) {}

  std::optional<T> value_;
  std::string reason_;
};

}  // namespace mrslam
