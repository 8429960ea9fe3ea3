// raykernel/parallel.hpp: the one way raykernel runs work on several threads — the batch API, the Python
// module's batches and the CLI's renders all go through run_parts.
//
// Two promises, whatever the system allows:
//   - A thread that cannot be started (std::thread throws: a process or address-space limit, EAGAIN) is not
//     an error and never std::terminate: the work goes to the threads that did start, the calling thread at
//     least. Every part runs exactly once, so the results are the same whichever threads ran them.
//   - A request for more threads than max_threads is capped at max_threads (a thread per core is what
//     gains; thousands only cost stacks).
#pragma once

#include <cstddef>
#include <functional>

namespace raykernel {

// The most threads one call starts, the calling thread included.
inline constexpr unsigned max_threads = 256;

// The threads a request means: 0 → as many as the hardware has (at least 1); above max_threads → max_threads.
[[nodiscard]] unsigned thread_count(unsigned requested) noexcept;

// Runs part(k) for every k in [0, parts), each once, on the calling thread and up to threads − 1 threads it
// starts (threads as thread_count gives it; parts are handed out one at a time, in order). After every
// thread has joined, rethrows the exception of the lowest k whose part threw; the parts after a throw may or
// may not have run. Returns the number of threads that ran parts (the caller included).
unsigned run_parts(std::size_t parts, unsigned threads, const std::function<void(std::size_t)>& part);

}  // namespace raykernel
