#pragma once
// The daemon's own files (the camera classifier's model, the dashboard) found wherever it was started from. A
// configured path that is absolute, or that exists from the working folder, is used as it is; a relative one that
// does not is looked for, in order:
//   1. in the source tree above the binary (build/daemon/fsd → the checkout: a developer's build),
//   2. under the install prefix beside the binary (/usr/local/bin/fsd → /usr/local/share/fsd/<path>),
//   3. under the prefix compiled in (CMAKE_INSTALL_PREFIX/share/fsd/<path>).
// What none of them has stays as configured, so that the error names the configured path.
#include <string>

#include "common/config.hpp"

namespace fsd {

std::string locate_resource(const std::string& configured);

// perception.camera.classifier.model and web.web_root in `cfg`, each set to where locate_resource found it.
void locate_resources(Config& cfg);

}  // namespace fsd
