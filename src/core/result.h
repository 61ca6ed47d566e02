// core/result.h — error values for everything that can fail on user input.
//
// The library never prints and never exits. A function that reads a file or validates a
// user parameter returns Result<T>: either a value or an Error whose message names the file,
// key or value at fault ("cannot read 'sky.exr': file is truncated"). The CLI prints the
// message and exits non-zero. Internal invariants are checked with assert() in debug builds.
#pragma once

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace footprint {

struct Error {
    std::string message;
};

// A value of type T or an Error (a small stand-in for C++23 std::expected).
template <class T>
class [[nodiscard]] Result {
  public:
    Result(T value) : state_(std::move(value)) {}
    Result(Error error) : state_(std::move(error)) {}

    bool ok() const { return state_.index() == 0; }
    explicit operator bool() const { return ok(); }

    T& value() & {
        assert(ok());
        return std::get<0>(state_);
    }
    const T& value() const& {
        assert(ok());
        return std::get<0>(state_);
    }
    T&& value() && {
        assert(ok());
        return std::get<0>(std::move(state_));
    }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }

    const Error& error() const {
        assert(!ok());
        return std::get<1>(state_);
    }

  private:
    std::variant<T, Error> state_;
};

// Success or an Error, for operations without a value (saving a file).
class [[nodiscard]] Status {
  public:
    Status() = default;
    Status(Error error) : error_(std::move(error)), ok_(false) {}
    bool ok() const { return ok_; }
    explicit operator bool() const { return ok_; }
    const Error& error() const {
        assert(!ok_);
        return error_;
    }

  private:
    Error error_;
    bool ok_ = true;
};

}  // namespace footprint
