// The last line of defence of every command: an exception that no command handles (not enough memory, a
// library error that should not happen) becomes one message and exit status 2, never std::terminate. So
// that "not enough memory" can say for what, a command names what it is doing with a Doing in scope.
#pragma once

#include <exception>
#include <string>
#include <string_view>

namespace raykernel::cli {

// Names what the command is doing while it is in scope (nested: the innermost is named): "reading the
// mesh file 'bunny.obj'". Main thread only.
class Doing {
 public:
  explicit Doing(std::string what);
  ~Doing();
  Doing(const Doing&) = delete;
  Doing& operator=(const Doing&) = delete;

 private:
  int exceptions_;  // std::uncaught_exceptions() at construction: more at destruction means unwinding
};

// What the innermost Doing an exception unwound named, else the innermost in scope ("" when none).
[[nodiscard]] std::string what_is_being_done();

// Prints the message for an exception that reached main — "raykernel COMMAND: not enough memory for
// WHAT" for std::bad_alloc, "raykernel COMMAND: WHAT()" for the others — and returns exit status 2.
[[nodiscard]] int report_uncaught(std::string_view command, const std::exception_ptr& failure) noexcept;

}  // namespace raykernel::cli
