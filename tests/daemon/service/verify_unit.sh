#!/usr/bin/env bash
# `systemd-analyze verify` on the service unit (CTest deploy.SystemdUnitVerifies): the unit with ExecStart on the
# built binary must verify with no complaint at all (systemd-analyze exits 0 on unknown keys; its output says so).
set -euo pipefail
unit="$1" fsd="$2"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
sed "s#/usr/local/bin/fsd#$fsd#" "$unit" > "$dir/fsd.service"
grep -q '^Type=notify$' "$dir/fsd.service" || { echo "fsd.service: not Type=notify"; exit 1; }
grep -q '^WatchdogSec=' "$dir/fsd.service" || { echo "fsd.service: no WatchdogSec"; exit 1; }
grep -q '^Restart=on-failure$' "$dir/fsd.service" || { echo "fsd.service: not Restart=on-failure"; exit 1; }
out="$(systemd-analyze verify "$dir/fsd.service" 2>&1)" || { echo "$out"; exit 1; }
if [[ -n "$out" ]]; then
  echo "systemd-analyze verify complained:"
  echo "$out"
  exit 1
fi
echo "fsd.service verifies"
