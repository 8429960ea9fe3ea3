// raykernel::DefaultFpEnvironment (raykernel/fp_environment.hpp): the outermost scope on a thread saves the
// caller's environment and installs the default with the same FpEnvironmentScope every entry point uses.
#include <raykernel/fp_environment.hpp>

#include "core/fp_environment.hpp"

#include <optional>

namespace raykernel {
namespace detail {

constinit thread_local int default_environment_scopes = 0;

namespace {
thread_local std::optional<FpEnvironmentScope> outermost_scope;
}  // namespace

}  // namespace detail

DefaultFpEnvironment::DefaultFpEnvironment() noexcept {
  if (detail::default_environment_scopes == 0) detail::outermost_scope.emplace();
  ++detail::default_environment_scopes;
}

DefaultFpEnvironment::~DefaultFpEnvironment() {
  if (--detail::default_environment_scopes == 0) detail::outermost_scope.reset();
}

}  // namespace raykernel
