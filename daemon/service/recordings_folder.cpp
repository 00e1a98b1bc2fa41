#include "daemon/service/recordings_folder.hpp"

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "common/logging.hpp"

namespace fsd {

namespace fs = std::filesystem;

std::string next_recording_path(const ServiceSettings& s) {
  std::error_code ec;
  fs::create_directories(s.recordings_dir, ec);
  if (!fs::is_directory(s.recordings_dir, ec))
    throw std::invalid_argument("service.recordings_dir: '" + s.recordings_dir + "' is not a folder that can be made");
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  localtime_r(&now, &tm);
  char name[64];
  std::strftime(name, sizeof name, "fsd-%Y%m%d-%H%M%S.mcap", &tm);
  return (fs::path(s.recordings_dir) / name).string();
}

int prune_recordings(const ServiceSettings& s, const std::string& keep) {
  if (s.recordings_dir.empty()) return 0;
  struct File {
    fs::path path;
    fs::file_time_type mtime;
    std::uintmax_t size;
  };
  std::vector<File> files;
  std::uintmax_t total = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(s.recordings_dir, ec)) {
    if (!e.is_regular_file(ec) || e.path().extension() != ".mcap") continue;
    const auto size = e.file_size(ec);
    if (ec) continue;
    files.push_back({e.path(), e.last_write_time(ec), size});
    total += size;
  }
  std::sort(files.begin(), files.end(), [](const File& a, const File& b) { return a.mtime < b.mtime; });
  const auto cap = static_cast<std::uintmax_t>(s.recordings_max_mb * 1024 * 1024);
  int removed = 0;
  for (const auto& f : files) {
    if (total <= cap) break;
    if (!keep.empty() && fs::equivalent(f.path, keep, ec)) continue;
    if (!fs::remove(f.path, ec)) continue;
    total -= f.size;
    ++removed;
    logger("service")->info("recordings over {:.0f} MiB: removed the oldest, {}", s.recordings_max_mb, f.path.string());
  }
  return removed;
}

}  // namespace fsd
