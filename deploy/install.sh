#!/usr/bin/env bash
# Installs a built fsd on the car's computer (`make install`, as root): the binary, its model and dashboard under
# PREFIX/share/fsd (where fsd finds them wherever it is started from), the configuration in /etc/fsd (kept when
# it is there), the systemd unit, the udev rules, the service's user. docs/operations.md says what follows.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${BUILD:-build}"
prefix="${PREFIX:-/usr/local}"
[[ -x "$build/daemon/fsd" ]] || { echo "build first: make build" >&2; exit 2; }
install -D -m 0755 "$build/daemon/fsd" "$prefix/bin/fsd"
# The camera's cone classifier (fsd train-classifier writes it; perception.camera.classifier.model reads it) and the
# dashboard, at the paths the configuration names, below PREFIX/share/fsd.
install -D -m 0644 perception/models/cone_hog_svm.json "$prefix/share/fsd/perception/models/cone_hog_svm.json"
if [[ -d web/dashboard/dist ]]; then
  rm -rf "$prefix/share/fsd/web/dashboard/dist" && mkdir -p "$prefix/share/fsd/web/dashboard"
  cp -r web/dashboard/dist "$prefix/share/fsd/web/dashboard/dist"
fi
install -D -m 0644 docs/operations.md "$prefix/share/doc/fsd/operations.md"
install -d /etc/fsd
# The configuration: the defaults with the car's paths, once. An existing one is the team's: never overwritten
# (a copy of every version goes to /etc/fsd/history/ when it changes: docs/operations.md, rolling back).
if [[ ! -f /etc/fsd/config.json ]]; then
  cp deploy/config/car.json /etc/fsd/config.json
  chmod 0644 /etc/fsd/config.json
fi
"$prefix/bin/fsd" config check /etc/fsd/config.json
install -d -m 0755 /etc/fsd/history
cp /etc/fsd/config.json "/etc/fsd/history/config-$(date +%Y%m%d-%H%M%S).json"
id fsd >/dev/null 2>&1 || useradd --system --no-create-home --groups dialout,video fsd
sed "s#/usr/local/bin/fsd#$prefix/bin/fsd#" deploy/fsd.service > /etc/systemd/system/fsd.service
chmod 0644 /etc/systemd/system/fsd.service
install -m 0644 deploy/99-fsd.rules /etc/udev/rules.d/99-fsd.rules
if [[ -d /run/systemd/system ]]; then
  systemctl daemon-reload
  udevadm control --reload 2>/dev/null || true
fi
echo "installed in $prefix; start with: systemctl enable --now fsd (journalctl -u fsd follows it)"
