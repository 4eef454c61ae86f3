#pragma once
// Errors across module boundaries: a Result<T> holds a value or an Error with a
// one-line message that names the file, the place and the reason. No exceptions
// cross module boundaries; asserts are for programmer errors only.
#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace body {

// Exit codes shared by bodygen and bodyview.
enum ExitCode : int { kExitOk = 0, kExitRuntime = 1, kExitBadInput = 2 };

struct Error {
    std::string message;
    int exit_code = kExitBadInput;  // bad input unless said otherwise
};

inline Error input_error(std::string message) { return Error{std::move(message), kExitBadInput}; }
inline Error runtime_error(std::string message) { return Error{std::move(message), kExitRuntime}; }

template <typename T>
class [[nodiscard]] Result {
public:
    Result(T value) : storage_(std::move(value)) {}
    Result(Error error) : storage_(std::move(error)) {}

    bool ok() const { return std::holds_alternative<T>(storage_); }
    explicit operator bool() const { return ok(); }

    T& value() & {
        assert(ok());
        return std::get<T>(storage_);
    }
    const T& value() const& {
        assert(ok());
        return std::get<T>(storage_);
    }
    T&& value() && {
        assert(ok());
        return std::get<T>(std::move(storage_));
    }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }

    const Error& error() const {
        assert(!ok());
        return std::get<Error>(storage_);
    }

private:
    std::variant<T, Error> storage_;
};

// Result<void> equivalent.
struct Ok {};
using Status = Result<Ok>;
inline Status ok_status() { return Ok{}; }

}  // namespace body
