#!/usr/bin/env bash
# Installs every build and test dependency of fsd-daemon from Debian's packages and the dashboard's npm packages.
# Idempotent and fast when everything is present: apt-get is not run at all then.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

# One list; each entry is a Debian package name. Keep it minimal: --no-install-recommends below.
packages=(
  build-essential cmake ninja-build pkg-config git ca-certificates
  libeigen3-dev libpcl-dev libopencv-dev
  libboost-dev libboost-system-dev libboost-program-options-dev
  nlohmann-json3-dev libfastrtps-dev libfastcdr-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libpcap-dev libspdlog-dev libfmt-dev libcli11-dev libzstd-dev liblz4-dev
  libceres-dev libnanoflann-dev ccache
  fastddsgen cyclonedds-dev cyclonedds-tools libsystemd-dev systemd
  clang libclang-rt-14-dev tcpdump
  nodejs npm chromium
)

missing=()
for p in "${packages[@]}"; do
  # dpkg-query is cheap; only packages not installed are handed to apt.
  status="$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)"
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
# npm may come from a non-Debian node install; accept any working npm.
if command -v npm >/dev/null 2>&1; then
  filtered=(); for p in "${missing[@]}"; do [[ "$p" == npm || "$p" == nodejs ]] || filtered+=("$p"); done
  missing=("${filtered[@]+"${filtered[@]}"}")
fi

if ((${#missing[@]})); then
  echo "install-deps: installing ${#missing[@]} Debian packages: ${missing[*]}"
  sudo_cmd=(); [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "install-deps: all Debian packages present"
fi

# Front end: install from the committed lockfile only when node_modules is missing or older than the lockfile.
dash="$here/web/dashboard"
if [[ -f "$dash/package-lock.json" ]]; then
  if [[ ! -d "$dash/node_modules" || "$dash/package-lock.json" -nt "$dash/node_modules/.package-lock.json" ]]; then
    echo "install-deps: npm ci in web/dashboard"
    (cd "$dash" && npm ci --no-audit --no-fund --loglevel=error)
  fi
fi
