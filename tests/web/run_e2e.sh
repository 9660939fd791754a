#!/usr/bin/env bash
# Runs the viewer's end-to-end browser test (CTest: viewer_e2e). Exits 77 (skipped) with a
# message when Debian's Chromium or Node is missing; installs playwright-core from the
# lockfile (npm ci) when node_modules is absent. Usage: run_e2e.sh GLINT_BINARY WORK_FOLDER
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
if [ ! -x /usr/bin/chromium ]; then
  echo "SKIPPED: /usr/bin/chromium is not installed (scripts/install-deps.sh installs Debian's chromium)"
  exit 77
fi
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "SKIPPED: node and npm are needed for the browser test"
  exit 77
fi
if [ ! -d "$here/node_modules/playwright-core" ]; then
  (cd "$here" && npm ci --no-audit --no-fund --loglevel=error)
fi
mkdir -p "$2"
exec node "$here/viewer_e2e.mjs" "$1" "$2"
