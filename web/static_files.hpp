#pragma once
// The dashboard's files under the web root. A request path never leaves the root: ".." segments (also
// percent-encoded), backslashes, NUL bytes and symlinks that point outside are refused.
#include <filesystem>
#include <string>
#include <string_view>

namespace fsd::web {

class StaticFiles {
 public:
  // `root` need not exist; then every file is NotFound and available() is false.
  explicit StaticFiles(const std::filesystem::path& root);

  enum class Status { Ok, NotFound, Forbidden, BadRequest };
  struct Result {
    Status status = Status::NotFound;
    std::filesystem::path file;  // canonical path of the file when Ok
    std::string content_type;
    bool immutable = false;  // content-hashed build asset: cacheable forever
  };
  // `path` is the request path without the query, still percent-encoded. "/" and folders map to index.html.
  Result resolve(std::string_view path) const;
  bool available() const { return !root_.empty(); }
  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path root_;  // canonical, empty when missing
};

std::string content_type_for(const std::filesystem::path& file);

// Where a configured web root is: as given when absolute or found from the working directory; else, for a
// relative path, the source tree two levels above the running executable (build/daemon/fsd → project root),
// then the source tree the binary was built from. Returns the path as given when none exists.
std::filesystem::path locate_web_root(const std::string& configured);

}  // namespace fsd::web
