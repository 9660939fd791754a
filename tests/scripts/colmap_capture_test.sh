#!/usr/bin/env bash
# CTest colmap_capture: synthesizes a tiny capture of builtin:gallery, reconstructs its
# cameras with Debian's colmap through scripts/colmap-capture.sh, and opens the result with
# `glint info` (Dataset::open and every buffer). Exits 77 (skipped) when colmap is absent.
# Usage: colmap_capture_test.sh GLINT_BINARY WORK_FOLDER
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
if ! command -v colmap >/dev/null; then
  echo "SKIPPED: colmap is not installed (scripts/install-deps.sh --colmap installs it)"
  exit 77
fi
glint="$1"
work="$2"
rm -rf "$work"
mkdir -p "$work"

# The shortest run that registers every view: 12 views 30 degrees apart at 160x120, few
# samples (SIFT needs the texture, not converged lighting).
"$glint" synth builtin:gallery -o "$work/synth" --layout capture --train 12 --res 160x120 --spp 8 \
  --bounces 3 --points 500
"$here/../../scripts/colmap-capture.sh" "$work/synth" "$work/colmap" | tee "$work/colmap.log"
registered="$(sed -n 's/.*registered \([0-9]*\) of \([0-9]*\) images.*/\1/p' "$work/colmap.log")"
if [ -z "$registered" ] || [ "$registered" -lt 10 ]; then
  echo "FAILED: COLMAP registered ${registered:-no} images of 12 (at least 10 expected)"
  exit 1
fi
# Dataset::open on COLMAP's cameras, every buffer loaded, the depth fits reported.
"$glint" info "$work/colmap"
# Idempotent: a second run replaces its own output.
"$here/../../scripts/colmap-capture.sh" "$work/synth" "$work/colmap" >/dev/null
echo "PASSED: $registered of 12 images registered"
