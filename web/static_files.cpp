#include "web/static_files.hpp"

#include <unistd.h>
#include <algorithm>
#include <array>
#include <system_error>

#include "web/url.hpp"

namespace fsd::web {

namespace fs = std::filesystem;

namespace {

bool within(const fs::path& file, const fs::path& root) {
  auto f = file.begin();
  for (auto r = root.begin(); r != root.end(); ++r, ++f)
    if (f == file.end() || *f != *r) return false;
  return true;
}

}  // namespace

StaticFiles::StaticFiles(const fs::path& root) {
  std::error_code ec;
  auto canon = fs::canonical(root, ec);
  if (!ec && fs::is_directory(canon, ec)) root_ = canon;
}

StaticFiles::Result StaticFiles::resolve(std::string_view path) const {
  Result r;
  if (path.empty() || path.front() != '/') {
    r.status = Status::BadRequest;
    return r;
  }
  const auto decoded = percent_decode(path);
  if (!decoded || decoded->find('\\') != std::string::npos) {
    r.status = Status::BadRequest;
    return r;
  }
  // Check every segment of the decoded path: no "..", no ".", nothing absolute ("//etc/passwd").
  std::string rel = decoded->substr(1);
  if (!rel.empty() && rel.front() == '/') {
    r.status = Status::Forbidden;
    return r;
  }
  std::size_t start = 0;
  while (start <= rel.size()) {
    const auto slash = rel.find('/', start);
    const auto seg =
        std::string_view(rel).substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    if (seg == ".." || seg == ".") {
      r.status = Status::Forbidden;
      return r;
    }
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  if (!available()) return r;
  fs::path candidate = root_ / fs::path(rel).relative_path();
  std::error_code ec;
  if (fs::is_directory(candidate, ec)) candidate /= "index.html";
  const auto canon = fs::canonical(candidate, ec);
  if (ec) return r;  // NotFound
  if (!within(canon, root_)) {
    r.status = Status::Forbidden;  // a symlink that points out of the root
    return r;
  }
  if (!fs::is_regular_file(canon, ec)) return r;
  r.status = Status::Ok;
  r.file = canon;
  r.content_type = content_type_for(canon);
  // Vite puts content-hashed bundles under assets/.
  r.immutable = rel.rfind("assets/", 0) == 0;
  return r;
}

std::string content_type_for(const fs::path& file) {
  static const std::array<std::pair<const char*, const char*>, 16> types{{
      {".html", "text/html; charset=utf-8"},
      {".js", "text/javascript; charset=utf-8"},
      {".mjs", "text/javascript; charset=utf-8"},
      {".css", "text/css; charset=utf-8"},
      {".json", "application/json"},
      {".map", "application/json"},
      {".svg", "image/svg+xml"},
      {".png", "image/png"},
      {".jpg", "image/jpeg"},
      {".jpeg", "image/jpeg"},
      {".ico", "image/x-icon"},
      {".webp", "image/webp"},
      {".woff2", "font/woff2"},
      {".wasm", "application/wasm"},
      {".txt", "text/plain; charset=utf-8"},
      {".webmanifest", "application/manifest+json"},
  }};
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const auto& [e, t] : types)
    if (ext == e) return t;
  return "application/octet-stream";
}

fs::path locate_web_root(const std::string& configured) {
  const fs::path p(configured);
  std::error_code ec;
  if (p.is_absolute() || fs::is_directory(p, ec)) return p;
  const auto exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto candidate = exe.parent_path().parent_path().parent_path() / p;
    if (fs::is_directory(candidate, ec)) return candidate;
  }
#ifdef FSD_SOURCE_DIR
  // A build tree elsewhere: the source tree this binary was built from.
  if (const auto candidate = fs::path(FSD_SOURCE_DIR) / p; fs::is_directory(candidate, ec)) return candidate;
#endif
  return p;
}

}  // namespace fsd::web
