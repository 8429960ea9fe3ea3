// The threads of `raykernel render`: image rows handed out one at a time (raykernel::run_parts, the one
// thread pool of the library, the Python module and the CLI).
#pragma once

#include <cstdint>
#include <functional>

namespace raykernel::cli {

// Runs `row_job(row)` for every row in [0, rows) on up to `threads` threads, the calling one included (0:
// every core; rows handed out one at a time, so uneven rows balance; threads the system refuses to start are
// no error), calling `progress` (if set) about every 100 ms with the fraction done — from one thread at a
// time — and with 1 at the end. Rethrows the first exception a job threw (no more rows start then). Returns
// the number of threads that ran rows.
unsigned for_each_row(std::uint32_t rows, unsigned threads, const std::function<void(double fraction)>& progress,
                  const std::function<void(std::uint32_t row)>& row_job);

}  // namespace raykernel::cli
