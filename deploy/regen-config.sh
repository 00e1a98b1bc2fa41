#!/usr/bin/env bash
# Regenerates deploy/config/default.json and the reference table of docs/configuration.md from the schema
# compiled into fsd (tests fail when either drifts from the code).
set -euo pipefail
cd "$(dirname "$0")/.."
fsd=${FSD:-build/daemon/fsd}
"$fsd" config defaults > deploy/config/default.json
head="$(sed '/^<!-- BEGIN GENERATED TABLE -->$/q' docs/configuration.md)"
tail="$(sed -n '/^<!-- END GENERATED TABLE -->$/,$p' docs/configuration.md)"
{ printf '%s\n' "$head"; "$fsd" config doc; printf '%s\n' "$tail"; } > docs/configuration.md.new
mv docs/configuration.md.new docs/configuration.md
