// The exit statuses of every command (docs/contract.md §3).
#pragma once

namespace raykernel::cli {

inline constexpr int exit_ok = 0;
inline constexpr int exit_invalid_line = 1;
inline constexpr int exit_usage = 2;  // a usage error, an I/O error, an input that is not what it should be

}  // namespace raykernel::cli
