#!/usr/bin/env bash
# Installs a built fsd on the car's computer: binary, dashboard, config, service unit, udev rules.
set -euo pipefail
cd "$(dirname "$0")/.."
[[ -x build/daemon/fsd ]] || { echo "build first: make build" >&2; exit 2; }
install -D -m 0755 build/daemon/fsd /usr/local/bin/fsd
if [[ -d web/dashboard/dist ]]; then
  mkdir -p /usr/local/share/fsd && rm -rf /usr/local/share/fsd/dashboard
  cp -r web/dashboard/dist /usr/local/share/fsd/dashboard
fi
# The camera's cone classifier (fsd train-classifier writes it; perception.camera.classifier.model reads it).
install -D -m 0644 perception/models/cone_hog_svm.json /usr/local/share/fsd/models/cone_hog_svm.json
install -d /etc/fsd
# The service runs from /: its dashboard and model are the installed copies, not the checkout's.
if [[ ! -f /etc/fsd/config.json ]]; then
  sed -e 's#"web_root": "web/dashboard/dist"#"web_root": "/usr/local/share/fsd/dashboard"#' \
      -e 's#"model": "perception/models/cone_hog_svm.json"#"model": "/usr/local/share/fsd/models/cone_hog_svm.json"#' \
      deploy/config/default.json > /etc/fsd/config.json
  chmod 0644 /etc/fsd/config.json
fi
fsd config check /etc/fsd/config.json
id fsd >/dev/null 2>&1 || useradd --system --no-create-home --groups dialout fsd
install -m 0644 deploy/fsd.service /etc/systemd/system/fsd.service
install -m 0644 deploy/99-fsd.rules /etc/udev/rules.d/99-fsd.rules
systemctl daemon-reload || true
echo "installed; start with: systemctl enable --now fsd"
