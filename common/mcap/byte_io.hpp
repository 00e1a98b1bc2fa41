#pragma once
// Where MCAP bytes go and come from: an abstract sink for the writer (a file, or memory for tests and tools), and
// a read-only memory map of a file for the readers, which work on one contiguous span of bytes.
#include <cstdint>
#include <span>
#include <string>

#include "common/mcap/records.hpp"

namespace fsd::mcap {

class ByteSink {
 public:
  virtual ~ByteSink() = default;
  // Takes all of `bytes` or throws McapError saying why (a full disk is an error, never silently dropped data).
  virtual void write(std::span<const std::uint8_t> bytes) = 0;
  virtual void flush() {}
};

class BufferSink final : public ByteSink {
 public:
  void write(std::span<const std::uint8_t> bytes) override { data.insert(data.end(), bytes.begin(), bytes.end()); }
  Bytes data;
};

// A file created (or truncated) for writing. Every write(2) error, ENOSPC and EIO included, throws McapError
// naming the file and the OS's reason; flush() hands the data to the kernel (fdatasync), close() on destruction.
class FileSink final : public ByteSink {
 public:
  explicit FileSink(const std::string& path);
  ~FileSink() override;
  FileSink(const FileSink&) = delete;
  FileSink& operator=(const FileSink&) = delete;
  void write(std::span<const std::uint8_t> bytes) override;
  void flush() override;
  void close();  // throws McapError when the kernel reports a delayed write error

 private:
  std::string path_;
  int fd_ = -1;
};

// A whole file mapped read-only. Throws McapError (without the path) when it cannot be opened or mapped; an empty
// file maps to an empty span (the readers give "empty file" for it).
class MappedFile {
 public:
  explicit MappedFile(const std::string& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  std::span<const std::uint8_t> bytes() const { return {data_, size_}; }

 private:
  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace fsd::mcap
