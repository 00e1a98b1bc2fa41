// libFuzzer target: arbitrary bytes as a capture file for the pcap reader (written to a temporary file, as the
// reader opens files). Every datagram it returns must lie inside the record it came from.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "drivers/vlp16/pcap_reader.hpp"

namespace {
// The scratch file, on tmpfs when there is one (a file on disk costs milliseconds per run). libFuzzer ends
// with _Exit, so each run removes it rather than a destructor.
struct ScratchFile {
  std::string path = std::string(::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp") + "/vlp16_pcap_fuzz_" +
                     std::to_string(::getpid()) + ".pcap";
};
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const ScratchFile scratch;
  const std::string& path = scratch.path;
  struct Remove {
    const std::string& path;
    ~Remove() { std::remove(path.c_str()); }
  } remove_after_run{path};
  if (FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  } else {
    return 0;
  }
  try {
    fsd::PcapReader reader(path);
    fsd::UdpDatagram d;
    std::size_t payload_bytes = 0;
    while (reader.next(d)) {
      if (d.payload.size() > 65535) __builtin_trap();
      for (const auto b : d.payload) payload_bytes += b;  // touch every byte: ASan checks the bounds
    }
    if (reader.counters().udp > reader.counters().records) __builtin_trap();
    if (payload_bytes > 255u * 65535u * reader.counters().udp) __builtin_trap();
  } catch (const fsd::PcapError&) {
    // corrupt input is expected to be rejected this way
  }
  return 0;
}
