// The floating-point environment the certified stages assume, checked and, where a caller left another
// one, set for the duration of a call and restored exactly (README, "Floating-point assumptions").
//
// The error bounds of the certified stages hold for binary64 arithmetic rounding to nearest with gradual
// underflow; the branch-free fast paths may also divide by zero or form inf − inf on inputs they then hand
// on, which must not trap. So every public entry point that computes runs in the default environment:
// round to nearest, no flush-to-zero (FTZ) or denormals-are-zero (DAZ), every exception masked. When the
// caller's environment is different (a program built with -ffast-math sets FTZ and DAZ at start-up;
// fesetround; feenableexcept), `FpEnvironmentScope` installs the default for the call. Either way it
// restores the caller's environment exactly on the way out — control bits and sticky status flags alike
// (the fast paths raise inexact, and on inputs they hand on also invalid or overflow) — also when the call
// throws.
//
// x86-64: the whole SSE control/status register MXCSR is read (stmxcsr) and, when needed, saved and
// restored; the x87 control word is left alone (the library does no x87 arithmetic). Elsewhere: the
// rounding mode (fegetround) and, on AArch64, FPCR's flush-to-zero bit and trap enables; the status flags
// are saved and restored with fegetenv/fesetenv.
#pragma once

#include <cstdint>

#if defined(__x86_64__) || defined(_M_X64)
#include <xmmintrin.h>
#else
#include <cfenv>
#endif

namespace raykernel::detail {

#if defined(__x86_64__) || defined(_M_X64)

// MXCSR bits 6–15: DAZ (6), the six exception masks (7–12, all set = masked), rounding control (13–14,
// 00 = to nearest), FTZ (15). Bits 0–5 are the sticky status flags, which do not change any result.
inline constexpr std::uint32_t mxcsr_control_mask = 0xFFC0u;
inline constexpr std::uint32_t mxcsr_default_control = 0x1F80u;

[[nodiscard]] inline bool fp_environment_is_default() noexcept {
  return (_mm_getcsr() & mxcsr_control_mask) == mxcsr_default_control;
}

class FpEnvironmentScope {
 public:
  FpEnvironmentScope() noexcept : caller_(_mm_getcsr()) {
    if ((caller_ & mxcsr_control_mask) != mxcsr_default_control) [[unlikely]]
      _mm_setcsr(mxcsr_default_control);
  }
  ~FpEnvironmentScope() { _mm_setcsr(caller_); }
  FpEnvironmentScope(const FpEnvironmentScope&) = delete;
  FpEnvironmentScope& operator=(const FpEnvironmentScope&) = delete;

 private:
  std::uint32_t caller_;
};

#else

#if defined(__aarch64__)
// FPCR: IOE, DZE, OFE, UFE, IXE, IDE (bits 8–12, 15) enable traps; FZ (24) flushes to zero; RMode (22–23).
inline std::uint64_t read_fpcr() noexcept {
  std::uint64_t r;
  __asm__ __volatile__("mrs %0, fpcr" : "=r"(r));
  return r;
}
inline constexpr std::uint64_t fpcr_checked_bits = (0x1Full << 8) | (1ull << 15) | (1ull << 24) | (3ull << 22);
#endif

[[nodiscard]] inline bool fp_environment_is_default() noexcept {
#if defined(__aarch64__)
  return (read_fpcr() & fpcr_checked_bits) == 0;
#else
  return std::fegetround() == FE_TONEAREST;
#endif
}

class FpEnvironmentScope {
 public:
  FpEnvironmentScope() noexcept : default_(fp_environment_is_default()) {
    if (default_) {
      std::fegetexceptflag(&flags_, FE_ALL_EXCEPT);
    } else {
      std::fegetenv(&caller_);
      std::fesetenv(FE_DFL_ENV);
    }
  }
  ~FpEnvironmentScope() {
    if (default_) std::fesetexceptflag(&flags_, FE_ALL_EXCEPT);
    else std::fesetenv(&caller_);
  }
  FpEnvironmentScope(const FpEnvironmentScope&) = delete;
  FpEnvironmentScope& operator=(const FpEnvironmentScope&) = delete;

 private:
  bool default_;
  std::fexcept_t flags_{};
  std::fenv_t caller_{};
};

#endif

// How many raykernel::DefaultFpEnvironment scopes are open on this thread (fp_environment.cpp): while one is,
// the default environment is installed and the caller has promised not to change it.
extern constinit thread_local int default_environment_scopes;

// f() in the default environment, leaving the caller's environment exactly as it found it; inside a
// DefaultFpEnvironment scope, just f().
template <class F>
[[gnu::always_inline]] inline decltype(auto) in_default_fp_environment(F&& f) {
  if (default_environment_scopes > 0) return f();
  const FpEnvironmentScope scope;
  return f();
}

}  // namespace raykernel::detail
