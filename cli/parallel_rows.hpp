// The threads of `raykernel render`: image rows handed out one at a time to a pool of workers.
#pragma once

#include <cstdint>
#include <functional>

namespace raykernel::cli {

// The number of worker threads for a request: `requested`, or every core when it is 0.
[[nodiscard]] unsigned worker_threads(unsigned requested) noexcept;

// Runs `row_job(row)` for every row in [0, rows) on `threads` threads (rows handed out one at a time, so
// uneven rows balance), calling `progress` (if set) from the calling thread about every 100 ms with the
// fraction done, and with 1 at the end. Rethrows the first exception a job threw (no more rows start then).
void for_each_row(std::uint32_t rows, unsigned threads, const std::function<void(double fraction)>& progress,
                  const std::function<void(std::uint32_t row)>& row_job);

}  // namespace raykernel::cli
