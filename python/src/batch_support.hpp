// What every vectorized binding shares: the choice of path, the error policy, threads over a C++ loop, and
// the walk through arrays that must be gathered into columns, the rows answered one by one through a scalar
// entry point, and the message naming an invalid row. The loops themselves are in bind_batch.cpp (planes),
// bind_triangle.cpp, bind_sphere.cpp and bind_mesh.cpp; none of them runs Python code, so they run with the GIL
// released.
#pragma once

#include "convert.hpp"

#include <raykernel/batch.hpp>
#include <raykernel/parallel.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <initializer_list>
#include <limits>
#include <mutex>
#include <cmath>
#include <optional>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

namespace raykernel::python {

// relation[i] (and location[i]) where valid[i] is false: not one of the enums' codes.
inline constexpr std::uint8_t invalid_code = 255;
inline constexpr double nan = std::numeric_limits<double>::quiet_NaN();

enum class Path { certified, exact, naive };

// "certified", "exact" or "naive" (the last only where `allow_naive`), or ValueError naming the choices.
[[nodiscard]] inline Path path_from(const std::string& path, bool allow_naive = true) {
  if (path == "certified") return Path::certified;
  if (path == "exact") return Path::exact;
  if (path == "naive" && allow_naive) return Path::naive;
  throw py::value_error(allow_naive ? "path: expected 'certified', 'exact' or 'naive', got '" + path + "'"
                                    : "path: expected 'certified' or 'exact', got '" + path + "'");
}

[[nodiscard]] inline unsigned threads_from(const std::optional<unsigned>& threads) { return threads.value_or(0); }

namespace batch_internal {
// The progress callback of the batch call running on this thread (ProgressScope), or none.
inline thread_local py::handle progress_callback;
// How often a long batch looks at Python (Ctrl-C, the progress callback) while its threads work.
inline constexpr std::chrono::milliseconds poll_interval{20};
inline constexpr std::chrono::milliseconds progress_interval{100};
}  // namespace batch_internal

// For the duration of a binding's call: `progress` (None, or a callable taking (done, total)) is the callback of
// the parallel_for loops the call runs on this thread. Set it before releasing the GIL.
class ProgressScope {
 public:
  explicit ProgressScope(py::handle progress) : previous_(batch_internal::progress_callback) {
    if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
      throw py::type_error("progress: expected None or a callable taking (done, total)");
    batch_internal::progress_callback = progress.is_none() ? py::handle() : progress;
  }
  ~ProgressScope() { batch_internal::progress_callback = previous_; }
  ProgressScope(const ProgressScope&) = delete;
  ProgressScope& operator=(const ProgressScope&) = delete;

 private:
  py::handle previous_;
};

// Runs work(begin, end) over [0, n) on up to `threads` threads (0: the hardware's; capped at
// raykernel::max_threads), at least `grain` items each, in blocks of grain/16; rethrows the first exception after
// all have joined. Threads the system will not start are no error (<raykernel/parallel.hpp>): the others do their
// parts.
//
// A long loop (n ≥ 8 grains, or a progress callback set) runs on its own threads while the calling thread, which
// has released the GIL, looks at Python every 20 ms: a pending signal (Ctrl-C: KeyboardInterrupt) or an exception
// from the progress callback stops the workers at their next block, and is raised once they have joined — within
// a block's time of the signal (microseconds for certified rows, one row for exact ones). The callback is called
// with (done, total) about every 0.1 s and once at the end with (total, total). The rows a stopped loop did not
// reach keep whatever the binding initialized them to; the binding's results are then not returned at all.
template <class Work>
void parallel_for(std::size_t n, unsigned threads, std::size_t grain, Work&& work) {
  grain = std::max<std::size_t>(grain, 1);
  const std::size_t count = std::max<std::size_t>(1, std::min<std::size_t>(thread_count(threads), n / grain));
  const std::size_t block = std::max<std::size_t>(1, grain / 16);
  std::atomic<bool> stop{false};
  std::atomic<std::size_t> done{0};
  const auto run = [&] {
    run_parts(count, static_cast<unsigned>(count), [&](std::size_t k) {
      const std::size_t end = n * (k + 1) / count;
      for (std::size_t begin = n * k / count; begin < end; begin += block) {
        if (stop.load(std::memory_order_relaxed)) return;
        const std::size_t stop_at = std::min(end, begin + block);
        work(begin, stop_at);
        done.fetch_add(stop_at - begin, std::memory_order_relaxed);
      }
    });
  };
  const py::handle callback = batch_internal::progress_callback;
  if (!callback && n < 8 * grain) return run();

  std::mutex mutex;
  std::condition_variable finished_signal;
  bool finished = false;
  std::exception_ptr failure, interruption;
  std::thread runner;
  try {
    runner = std::thread([&] {
      try {
        run();
      } catch (...) {
        failure = std::current_exception();
      }
      const std::lock_guard<std::mutex> lock(mutex);
      finished = true;
      finished_signal.notify_one();
    });
  } catch (const std::system_error&) {
    return run();  // no thread to spare: the loop runs here, without interruption
  }
  auto last_progress = std::chrono::steady_clock::now();
  const auto look_at_python = [&](bool final) {
    const py::gil_scoped_acquire gil;
    try {
      if (!final && PyErr_CheckSignals() != 0) throw py::error_already_set();
      const auto now = std::chrono::steady_clock::now();
      if (callback && (final || now - last_progress >= batch_internal::progress_interval)) {
        last_progress = now;
        callback(final ? n : done.load(std::memory_order_relaxed), n);
      }
    } catch (...) {
      interruption = std::current_exception();
      stop.store(true, std::memory_order_relaxed);
    }
  };
  {
    std::unique_lock<std::mutex> lock(mutex);
    while (!finished_signal.wait_for(lock, batch_internal::poll_interval, [&] { return finished; })) {
      lock.unlock();
      if (!interruption) look_at_python(false);
      lock.lock();
    }
  }
  runner.join();
  if (interruption) std::rethrow_exception(interruption);
  if (failure) std::rethrow_exception(failure);
  if (callback) {
    look_at_python(true);
    if (interruption) std::rethrow_exception(interruption);
  }
}

// f with a trailing `progress` argument (None or a callable): f(a...) run in a ProgressScope. Every batch binding
// whose rows go through parallel_for is registered through it, with py::arg("progress") = py::none() last.
template <class R, class... A>
[[nodiscard]] auto with_progress(R (*f)(A...)) {
  return [f](A... a, shown::Progress progress) -> R {
    const ProgressScope scope(progress);
    return f(std::forward<A>(a)...);
  };
}

// Items per thread below which a thread costs more than it saves: exact queries take microseconds, certified
// ones tens of nanoseconds, naive ones a few.
inline constexpr std::size_t exact_grain = 256;
inline constexpr std::size_t certified_grain = std::size_t{1} << 13;
inline constexpr std::size_t naive_grain = std::size_t{1} << 15;

[[nodiscard]] inline std::size_t grain_of(Path path) {
  return path == Path::exact ? exact_grain : path == Path::certified ? certified_grain : naive_grain;
}

// Rows per call into the batch API when an input must be gathered into columns (a row-major array): the
// gathered chunk stays in cache for the batch, and a large array is never copied whole. 2^16 queries are
// still enough for the batch API to split over threads.
inline constexpr std::size_t gather_chunk = std::size_t{1} << 16;

// Calls work(begin, end) over [0, n) in chunks: one chunk when every view is contiguous, else gather_chunk rows.
template <class Work>
void in_chunks(std::size_t n, std::initializer_list<const ColumnsView*> views, Work&& work) {
  bool contiguous = true;
  for (const ColumnsView* v : views) contiguous = contiguous && v->contiguous();
  const std::size_t step = contiguous ? std::max<std::size_t>(n, 1) : gather_chunk;
  for (std::size_t begin = 0; begin < n; begin += step) work(begin, std::min(n, begin + step));
}

[[nodiscard]] inline RayBatch ray_batch(ColumnsView& o, ColumnsView& d, std::size_t begin, std::size_t end) {
  const auto oc = o.columns(begin, end), dc = d.columns(begin, end);
  return {oc[0], oc[1], oc[2], dc[0], dc[1], dc[2]};
}

// Why a point row cannot be asked about, or nothing: the kernel's point queries (inside, closest_point) throw for a
// non-finite point; a batch checks first, so that a bad row is named and, with errors="mask", skipped.
[[nodiscard]] inline std::optional<std::string> point_problem(const Vec3& p) {
  if (!std::isfinite(p.x)) return "x is not finite";
  if (!std::isfinite(p.y)) return "y is not finite";
  if (!std::isfinite(p.z)) return "z is not finite";
  return std::nullopt;
}

// The first row whose valid[i] is false, if any.
[[nodiscard]] inline std::optional<std::size_t> first_invalid_row(std::span<const bool> valid) {
  const auto it = std::find(valid.begin(), valid.end(), false);
  if (it == valid.end()) return std::nullopt;
  return static_cast<std::size_t>(it - valid.begin());
}

// The message of invalid row i: "query 17: REASON" (query i is ray i against primitive i), or "ray 17: REASON"
// (every ray against one primitive).
[[nodiscard]] inline std::string row_error(std::size_t i, bool one_primitive, const std::string& reason) {
  return (one_primitive ? "ray " : "query ") + std::to_string(i) + ": " + reason;
}

// row_error for the first row whose valid[i] is false, if any; reason(i) is validate's answer for row i.
template <class Reason>
[[nodiscard]] std::optional<std::string> first_row_error(std::span<const bool> valid, bool one_primitive,
                                                         Reason&& reason) {
  const std::optional<std::size_t> i = first_invalid_row(valid);
  if (!i) return std::nullopt;
  return row_error(*i, one_primitive, reason(*i).value_or("invalid input"));
}

// Runs answer(i) for every row of [0, n) on up to `threads` threads (parallel_for), each row's valid[i] set
// true first. Where answer(i) throws invalid_input — the certified and exact entry points validate as they
// answer, so invalid input costs only where it occurs — valid[i] is set false and mark(i) gives the row its
// invalid answer. (A path that answers invalid input too, the naive one, sets valid[i] itself.)
template <class Answer, class Mark>
void answer_rows(std::size_t n, unsigned threads, std::size_t grain, std::span<bool> valid, Answer&& answer,
                 Mark&& mark) {
  parallel_for(n, threads, grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      valid[i] = true;
      try {
        answer(i);
      } catch (const invalid_input&) {
        valid[i] = false;
        mark(i);
      }
    }
  });
}

}  // namespace raykernel::python
