#include "rendering/parallel_rows.hpp"

#include <raykernel/parallel.hpp>

#include <atomic>
#include <chrono>
#include <mutex>

namespace raykernel::cli {

unsigned for_each_row(std::uint32_t rows, unsigned threads, const std::function<void(double)>& progress,
                  const std::function<void(std::uint32_t)>& row_job) {
  using clock = std::chrono::steady_clock;
  std::atomic<std::uint32_t> done{0};
  std::mutex reporting;  // held by the one thread reporting progress; the others do not wait for it
  clock::time_point last_report = clock::now();
  const unsigned ran = run_parts(rows, threads, [&](std::size_t row) {
    row_job(static_cast<std::uint32_t>(row));
    const std::uint32_t finished = done.fetch_add(1) + 1;
    if (!progress) return;
    const std::unique_lock<std::mutex> lock(reporting, std::try_to_lock);
    if (!lock.owns_lock()) return;
    const clock::time_point now = clock::now();
    if (now - last_report < std::chrono::milliseconds(100)) return;
    last_report = now;
    progress(static_cast<double>(finished) / rows);
  });
  if (progress) progress(1.0);
  return ran;
}

}  // namespace raykernel::cli
