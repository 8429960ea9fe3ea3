#include "common/io.hpp"

#include "common/exit_status.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iostream>

namespace raykernel::cli {

std::string system_reason(int error_number) { return std::strerror(error_number); }

// ---- Output ----------------------------------------------------------------------------------------------

FdOutputBuffer::FdOutputBuffer(int fd, std::size_t buffer_size) : fd_(fd), buffer_(buffer_size) {
  setp(buffer_.data(), buffer_.data() + buffer_.size());
}

FdOutputBuffer::~FdOutputBuffer() { (void)drain(); }

bool FdOutputBuffer::write_all(const char* data, std::size_t size) noexcept {
  if (error_ != 0) return false;
  while (size > 0) {
    const ssize_t n = ::write(fd_, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      error_ = errno;
      return false;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

bool FdOutputBuffer::drain() noexcept {
  const std::size_t pending = static_cast<std::size_t>(pptr() - pbase());
  const bool ok = write_all(pbase(), pending);
  setp(buffer_.data(), buffer_.data() + buffer_.size());  // a failed buffer drops what it holds
  return ok;
}

FdOutputBuffer::int_type FdOutputBuffer::overflow(int_type c) {
  if (!drain()) return traits_type::eof();
  if (!traits_type::eq_int_type(c, traits_type::eof())) {
    *pptr() = traits_type::to_char_type(c);
    pbump(1);
  }
  return traits_type::not_eof(c);
}

std::streamsize FdOutputBuffer::xsputn(const char* s, std::streamsize n) {
  if (error_ != 0) return 0;
  const auto size = static_cast<std::size_t>(n);
  if (size <= static_cast<std::size_t>(epptr() - pptr())) {
    std::memcpy(pptr(), s, size);
    pbump(static_cast<int>(n));
    return n;
  }
  // Larger than what is left: write the buffer, then the block directly (a PNG on standard output).
  if (!drain() || !write_all(s, size)) return 0;
  return n;
}

int FdOutputBuffer::sync() { return drain() ? 0 : -1; }

// ---- Input -----------------------------------------------------------------------------------------------

FdInputBuffer::FdInputBuffer(int fd, std::size_t buffer_size) : fd_(fd), buffer_(buffer_size) {
  setg(buffer_.data(), buffer_.data(), buffer_.data());
}

void FdInputBuffer::fail(std::string reason) {
  failure_ = std::move(reason);
  setg(buffer_.data(), buffer_.data(), buffer_.data());
}

FdInputBuffer::int_type FdInputBuffer::underflow() {
  if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
  if (error_ != 0 || !failure_.empty()) return traits_type::eof();
  while (true) {
    const ssize_t n = ::read(fd_, buffer_.data(), buffer_.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      error_ = errno;
      return traits_type::eof();
    }
    if (n == 0) return traits_type::eof();
    setg(buffer_.data(), buffer_.data(), buffer_.data() + n);
    return traits_type::to_int_type(*gptr());
  }
}

void use_checked_standard_streams() {
  // Never destroyed: the standard streams are flushed after static objects are destroyed, and must still
  // find their buffers then.
  static FdOutputBuffer* const out = new FdOutputBuffer(STDOUT_FILENO);
  static FdInputBuffer* const in = new FdInputBuffer(STDIN_FILENO);
  static FdOutputBuffer* const err = new FdOutputBuffer(STDERR_FILENO, 1 << 12);
  std::cout.rdbuf(out);
  std::cin.rdbuf(in);
  std::cerr.rdbuf(err);  // still unit-buffered: written at the end of every output operation
  if (::isatty(STDIN_FILENO) == 0) std::cin.tie(nullptr);
}

Input::Input(const std::string& path, Dash dash) {
  if ((path.empty() || path == "-") && dash == Dash::is_standard_input) {
    stream_ = &std::cin;
    return;
  }
  do fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  while (fd_ < 0 && errno == EINTR);
  if (fd_ < 0) {
    open_error_ = system_reason(errno);
    return;
  }
  // A directory opens, and fails only when read: say so now.
  struct stat status {};
  if (::fstat(fd_, &status) == 0 && S_ISDIR(status.st_mode)) {
    open_error_ = system_reason(EISDIR);
    ::close(fd_);
    fd_ = -1;
    return;
  }
  buffer_ = std::make_unique<FdInputBuffer>(fd_);
  owned_stream_ = std::make_unique<std::istream>(buffer_.get());
  stream_ = owned_stream_.get();
}

Input::~Input() {
  if (fd_ >= 0) ::close(fd_);
}

std::string Input::read_error() const {
  if (stream_ == nullptr) return {};
  if (const auto* fd_buffer = dynamic_cast<const FdInputBuffer*>(stream_->rdbuf())) {
    if (!fd_buffer->failure().empty()) return fd_buffer->failure();
    if (fd_buffer->error()) return system_reason(fd_buffer->error());
  }
  return stream_->bad() ? "read failed" : "";
}

// ---- The end of a command ----------------------------------------------------------------------------

bool flush_standard_output() {
  static bool reported = false;
  std::cout.flush();
  if (std::cout) return true;
  if (!reported) {
    reported = true;
    const auto* fd_buffer = dynamic_cast<const FdOutputBuffer*>(std::cout.rdbuf());
    const std::string reason = fd_buffer && fd_buffer->error() ? system_reason(fd_buffer->error()) : "write failed";
    std::cerr << "raykernel: I/O error writing standard output: " << reason << '\n';
  }
  return false;
}

int finish_standard_output(int status) {
  const bool output_ok = flush_standard_output();
  // A write to standard error that failed lost a message or output that was asked for (--stats, a render's
  // report when the image goes to standard output): an I/O error too, though it cannot be reported.
  std::cerr.flush();
  return output_ok && std::cerr ? status : exit_usage;
}

}  // namespace raykernel::cli
