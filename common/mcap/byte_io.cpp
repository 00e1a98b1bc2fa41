#include "common/mcap/byte_io.hpp"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace fsd::mcap {
namespace {

[[noreturn]] void os_error(const std::string& what, const std::string& path) {
  throw McapError(what + " " + path + ": " + std::strerror(errno));
}

// The reader's errors leave the path out: the caller prints "fsd: <file>: <what>".
[[noreturn]] void read_error(const std::string& what) { throw McapError(what + ": " + std::strerror(errno)); }

}  // namespace

FileSink::FileSink(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) os_error("cannot create", path);
}

FileSink::~FileSink() {
  if (fd_ >= 0) ::close(fd_);
}

void FileSink::write(std::span<const std::uint8_t> bytes) {
  if (fd_ < 0) throw McapError("writing " + path_ + ": the file is closed");
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      os_error("writing", path_);
    }
    bytes = bytes.subspan(static_cast<std::size_t>(n));
  }
}

void FileSink::flush() {
  if (fd_ >= 0 && ::fdatasync(fd_) != 0 && errno != EINVAL) os_error("flushing", path_);
}

void FileSink::close() {
  if (fd_ < 0) return;
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0 && errno != EINTR) os_error("closing", path_);
}

MappedFile::MappedFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) read_error("cannot open");
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    ::close(fd);
    read_error("cannot stat");
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    throw McapError("not a regular file");
  }
  size_ = static_cast<std::size_t>(st.st_size);
  if (size_ > 0) {
    void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    if (p == MAP_FAILED) {
      ::close(fd);
      read_error("cannot map");
    }
    data_ = static_cast<const std::uint8_t*>(p);
  }
  ::close(fd);
}

MappedFile::~MappedFile() {
  if (data_) ::munmap(const_cast<std::uint8_t*>(data_), size_);
}

}  // namespace fsd::mcap
