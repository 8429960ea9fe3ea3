#include "common/failure.hpp"

#include "common/exit_status.hpp"
#include "common/text_format.hpp"

#include <cstdio>
#include <iostream>
#include <new>
#include <vector>

namespace raykernel::cli {
namespace {

std::vector<std::string>& doing_stack() {
  static std::vector<std::string> stack;
  return stack;
}

// The innermost Doing that an exception unwound, kept for main's message (the Doing itself is gone by then).
std::string& unwound() {
  static std::string what;
  return what;
}

}  // namespace

Doing::Doing(std::string what) : exceptions_(std::uncaught_exceptions()) {
  unwound().clear();  // an exception that unwound an earlier Doing was handled: it is not main's to report
  doing_stack().push_back(std::move(what));
}

Doing::~Doing() {
  if (std::uncaught_exceptions() > exceptions_ && unwound().empty()) unwound() = std::move(doing_stack().back());
  doing_stack().pop_back();
}

std::string what_is_being_done() {
  if (!unwound().empty()) return unwound();
  return doing_stack().empty() ? std::string() : doing_stack().back();
}

int report_uncaught(std::string_view command, const std::exception_ptr& failure) noexcept {
  std::string message = "raykernel";
  try {
    if (!command.empty()) message.append(" ").append(printable(command));
    try {
      std::rethrow_exception(failure);
    } catch (const std::bad_alloc&) {
      const std::string what = what_is_being_done();
      message += ": not enough memory" + (what.empty() ? std::string() : " for " + what);
    } catch (const std::exception& e) {
      message.append(": ").append(printable(e.what()));
    } catch (...) {
      message += ": unknown error";
    }
  } catch (...) {
    message = "raykernel: not enough memory";  // even for the message: say what can be said
  }
  // Through stdio, not std::cerr: this must not allocate, and must not depend on the stream's state.
  std::fputs(message.c_str(), stderr);
  std::fputc('\n', stderr);
  std::fflush(stderr);
  return exit_usage;
}

}  // namespace raykernel::cli
