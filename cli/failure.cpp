#include "failure.hpp"

#include "commands.hpp"
#include "text_format.hpp"

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

}  // namespace

Doing::Doing(std::string what) { doing_stack().push_back(std::move(what)); }
Doing::~Doing() { doing_stack().pop_back(); }

std::string what_is_being_done() { return doing_stack().empty() ? std::string() : doing_stack().back(); }

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
