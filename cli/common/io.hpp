// The CLI's input and output with every read and write checked and the system's reason kept: stream
// buffers over file descriptors (read(2), write(2)), the input a command opens (standard input or a file),
// and the end of a command's output (docs/contract.md §3: an I/O error is exit status 2).
//
// iostreams report a failed write only as badbit, and errno is not reliably the failing call's by the time
// a caller looks; these buffers keep the errno of the first failing call, so that messages can say
// "No space left on device" or "Broken pipe". A buffer that failed stays failed: every later write (read)
// fails at once, so a stream over it goes bad and stays bad, and a loop that checks its stream stops.
#pragma once

#include <istream>
#include <memory>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

namespace raykernel::cli {

// Writes to a file descriptor it does not own, through a buffer (written when full, on flush, and on
// destruction). error() is the errno of the first failed write(2), 0 while none failed.
class FdOutputBuffer : public std::streambuf {
 public:
  explicit FdOutputBuffer(int fd, std::size_t buffer_size = 1 << 16);
  ~FdOutputBuffer() override;
  FdOutputBuffer(const FdOutputBuffer&) = delete;
  FdOutputBuffer& operator=(const FdOutputBuffer&) = delete;

  [[nodiscard]] int error() const noexcept { return error_; }

 protected:
  int_type overflow(int_type c) override;
  std::streamsize xsputn(const char* s, std::streamsize n) override;
  int sync() override;

 private:
  bool write_all(const char* data, std::size_t size) noexcept;  // false (and error_ set) on failure
  bool drain() noexcept;                                         // writes the buffered bytes
  int fd_;
  int error_ = 0;
  std::vector<char> buffer_;
};

// Reads a file descriptor it does not own. error() is the errno of the first failed read(2), 0 while none
// failed (end of file is not an error).
class FdInputBuffer : public std::streambuf {
 public:
  explicit FdInputBuffer(int fd, std::size_t buffer_size = 1 << 16);
  FdInputBuffer(const FdInputBuffer&) = delete;
  FdInputBuffer& operator=(const FdInputBuffer&) = delete;

  [[nodiscard]] int error() const noexcept { return error_; }
  // Marks the input failed for a reason of the reader's (a line too long): reading stops, and this is the
  // reason Input::read_error() gives.
  void fail(std::string reason);
  [[nodiscard]] const std::string& failure() const noexcept { return failure_; }

 protected:
  int_type underflow() override;

 private:
  int fd_;
  int error_ = 0;
  std::string failure_;
  std::vector<char> buffer_;
};

// Puts checked buffers under std::cout, std::cin and std::cerr (fd 1, 0 and 2), once, at the start of main. std::cin
// stays tied to std::cout (answers appear as lines are typed) only when standard input is a terminal.
void use_checked_standard_streams();

// The input of a command: standard input (std::cin) for "-" or "" (unless `dash` says "-" is a file's
// name), else the file, opened for reading.
class Input {
 public:
  enum class Dash { is_standard_input, is_a_file };
  explicit Input(const std::string& path, Dash dash = Dash::is_standard_input);
  ~Input();
  Input(const Input&) = delete;
  Input& operator=(const Input&) = delete;

  // Whether it opened; otherwise open_error() is the system's reason ("No such file or directory",
  // "Permission denied", "Is a directory").
  [[nodiscard]] bool is_open() const noexcept { return open_error_.empty(); }
  [[nodiscard]] const std::string& open_error() const noexcept { return open_error_; }
  [[nodiscard]] std::istream& stream() noexcept { return *stream_; }
  // After reading: why reading failed (the system's reason), or empty when it did not.
  [[nodiscard]] std::string read_error() const;

 private:
  int fd_ = -1;  // owned; -1 for standard input
  std::string open_error_;
  std::unique_ptr<FdInputBuffer> buffer_;
  std::unique_ptr<std::istream> owned_stream_;
  std::istream* stream_ = nullptr;
};

// Flushes std::cout. When a write or the flush failed, prints "raykernel: I/O error writing standard
// output: REASON" on stderr (the first time only) and returns false.
[[nodiscard]] bool flush_standard_output();

// The end of every command: `status` when everything written to std::cout and std::cerr reached them, else
// exit status 2 (exit_usage), after the message of flush_standard_output when std::cout failed.
[[nodiscard]] int finish_standard_output(int status);

// The system's text for an errno value ("No space left on device").
[[nodiscard]] std::string system_reason(int error_number);

}  // namespace raykernel::cli
