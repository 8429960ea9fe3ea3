// raykernel/fp_environment.hpp: paying for the floating-point environment once per loop, not once per call.
//
// Every raykernel entry point answers in the default floating-point environment (round to nearest, no
// flush-to-zero or denormals-are-zero, every exception masked) whatever the caller left: it reads the
// environment on entry, installs the default when the caller's differs, and restores the caller's on exit,
// status flags included (README, "Floating-point assumptions"). On x86-64 that read and that restore
// (stmxcsr, ldmxcsr) each wait for the floating-point operations in flight, so they cost about as much as a
// whole relation query (bench/README.md). A thread making many scalar calls can pay them once:
//
//   {
//     const raykernel::DefaultFpEnvironment env;  // this thread: the default environment, checked once
//     for (const Plane& p : planes) ... relation(ray, p) ...;   // no per-call read and restore
//   }                                                   // the environment as it was before the scope
//
// While a DefaultFpEnvironment lives on a thread, the entry points called on that thread trust it and skip
// their own check. The thread must therefore leave the environment alone inside the scope (no fesetround,
// feenableexcept, _mm_setcsr, fesetenv, nor a library call that does them): an environment changed inside
// the scope is the one case where an answer could be wrong. On destruction the environment of the
// construction is restored exactly, control bits and status flags: flags raised inside the scope, by
// raykernel or by the caller's own arithmetic, are cleared (as each unscoped call clears its own). Scopes
// nest (only the outermost saves and restores); other threads, the batch API's workers included, are not
// affected and keep checking per call. The object must be destroyed on the thread that created it.
#pragma once

namespace raykernel {

class DefaultFpEnvironment {
 public:
  DefaultFpEnvironment() noexcept;
  ~DefaultFpEnvironment();
  DefaultFpEnvironment(const DefaultFpEnvironment&) = delete;
  DefaultFpEnvironment& operator=(const DefaultFpEnvironment&) = delete;
};

}  // namespace raykernel
