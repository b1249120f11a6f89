// Result<T>: a value or a one-line error message naming the file/line/value (for outside input).
#pragma once

#include <cassert>
#include <optional>
#include <string>
#include <utility>

namespace sr {

template <class T>
class [[nodiscard]] Result {
public:
    Result(T value) : value_(std::move(value)) {}
    static Result failure(std::string message) {
        Result r;
        r.error_ = std::move(message);
        return r;
    }

    bool ok() const { return value_.has_value(); }
    explicit operator bool() const { return ok(); }
    const T& value() const& { assert(ok()); return *value_; }
    T& value() & { assert(ok()); return *value_; }
    T&& value() && { assert(ok()); return std::move(*value_); }
    const std::string& error() const { return error_; }

private:
    Result() = default;
    std::optional<T> value_;
    std::string error_;
};

// For operations that produce nothing but can fail.
struct Done {};
using Status = Result<Done>;
inline Status success() { return Status(Done{}); }

} // namespace sr
