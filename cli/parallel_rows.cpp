#include "parallel_rows.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace raykernel::cli {

unsigned worker_threads(unsigned requested) noexcept {
  return requested ? requested : std::max(1u, std::thread::hardware_concurrency());
}

void for_each_row(std::uint32_t rows, unsigned threads, const std::function<void(double)>& progress,
                  const std::function<void(std::uint32_t)>& row_job) {
  std::atomic<std::uint32_t> next{0}, done{0};
  std::exception_ptr failure;
  std::mutex mutex;
  std::condition_variable finished;
  auto worker = [&] {
    for (std::uint32_t row; (row = next.fetch_add(1)) < rows;) {
      try {
        row_job(row);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!failure) failure = std::current_exception();
        next = rows;  // stop handing out rows
      }
      if (done.fetch_add(1) + 1 == rows) {
        const std::lock_guard<std::mutex> lock(mutex);
        finished.notify_all();
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned k = 0; k < threads; ++k) pool.emplace_back(worker);
  {
    std::unique_lock<std::mutex> lock(mutex);
    while (done.load() < rows && !failure) {
      finished.wait_for(lock, std::chrono::milliseconds(100));
      if (progress) progress(static_cast<double>(done.load()) / rows);
    }
  }
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  if (progress) progress(1.0);
}

}  // namespace raykernel::cli
