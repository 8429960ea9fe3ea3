// The default floating-point environment for the duration of a reference check or a report, and the caller's
// restored exactly afterwards (control modes and raised flags): the checks (reference_check.cpp,
// triangle_reference_check.cpp) then read the same in any environment their caller left (printf and the
// stream formatting follow the rounding mode, and raise flags of their own). A testkit-internal header.
#pragma once

#include <cfenv>

namespace raykernel::testkit::internal {

class DefaultEnvironmentScope {
 public:
  DefaultEnvironmentScope() noexcept {
    std::fegetenv(&caller_);
    std::fesetenv(FE_DFL_ENV);
  }
  ~DefaultEnvironmentScope() { std::fesetenv(&caller_); }
  DefaultEnvironmentScope(const DefaultEnvironmentScope&) = delete;
  DefaultEnvironmentScope& operator=(const DefaultEnvironmentScope&) = delete;

 private:
  std::fenv_t caller_;
};

}  // namespace raykernel::testkit::internal
