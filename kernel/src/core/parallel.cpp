// run_parts (<raykernel/parallel.hpp>): parts handed out one at a time from an atomic counter to the calling
// thread and the threads it could start.
//
// Why a failed start cannot terminate: each std::thread is moved into `pool` only after its constructor
// returned, so `pool` holds only threads that run; a constructor that throws (std::system_error, or
// std::bad_alloc for its state) ends the starting, and the threads in `pool` are joined before run_parts
// returns or throws. No std::thread is ever destroyed while joinable.
#include <raykernel/parallel.hpp>

#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>
#include <vector>

namespace raykernel {

unsigned thread_count(unsigned requested) noexcept {
  const unsigned wanted = requested != 0 ? requested : std::max(1u, std::thread::hardware_concurrency());
  return std::min(wanted, max_threads);
}

unsigned run_parts(std::size_t parts, unsigned threads, const std::function<void(std::size_t)>& part) {
  const std::size_t wanted = std::min<std::size_t>(thread_count(threads), std::max<std::size_t>(parts, 1));
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::size_t failed_part = std::numeric_limits<std::size_t>::max();
  std::exception_ptr failure;
  auto worker = [&]() noexcept {
    for (std::size_t k; (k = next.fetch_add(1, std::memory_order_relaxed)) < parts;) {
      try {
        part(k);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (k < failed_part) {
          failed_part = k;
          failure = std::current_exception();
        }
        next.store(parts, std::memory_order_relaxed);  // hand out no more parts
      }
    }
  };
  std::vector<std::thread> pool;
  try {
    pool.reserve(wanted - 1);
    for (std::size_t k = 1; k < wanted; ++k) pool.push_back(std::thread(worker));
  } catch (...) {
    // Not started (or no room to keep it): the threads that did start, and this one, do all the parts.
  }
  worker();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  return static_cast<unsigned>(pool.size() + 1);
}

}  // namespace raykernel
