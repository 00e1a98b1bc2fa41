#include "daemon/service/resource_paths.hpp"

#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

namespace fsd {

namespace fs = std::filesystem;

std::string locate_resource(const std::string& configured) {
  const fs::path p(configured);
  std::error_code ec;
  if (configured.empty() || p.is_absolute() || fs::exists(p, ec)) return configured;
  std::vector<fs::path> candidates;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    candidates.push_back(exe.parent_path().parent_path().parent_path() / p);
    candidates.push_back(exe.parent_path().parent_path() / "share/fsd" / p);
  }
#ifdef FSD_INSTALL_PREFIX
  candidates.push_back(fs::path(FSD_INSTALL_PREFIX) / "share/fsd" / p);
#endif
  for (const auto& c : candidates)
    if (fs::exists(c, ec)) return c.lexically_normal().string();
  return configured;
}

void locate_resources(Config& cfg) {
  for (const char* key : {"perception.camera.classifier.model", "web.web_root"}) {
    const std::string configured = cfg.string(key);
    const std::string found = locate_resource(configured);
    if (found != configured) cfg.set(key, found, std::string(key) + " found from the binary's place");
  }
}

}  // namespace fsd
