#!/usr/bin/env bash
# CTest colmap_capture: synthesizes a small capture of builtin:gallery, reconstructs its
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

# The recipe of tests/data/colmap_gallery, the shortest found to register: 24 views 15
# degrees apart at 320x240 and 8 samples per pixel (12 views 30 degrees apart, 160x120, or
# 4 samples per pixel leave COLMAP without an initial pair of 100 inliers).
"$glint" synth builtin:gallery -o "$work/synth" --layout capture --train 24 --res 320x240 --spp 8 \
  --bounces 3 --points 500
"$here/../../scripts/colmap-capture.sh" "$work/synth" "$work/colmap" | tee "$work/colmap.log"
registered="$(sed -n 's/.*registered \([0-9]*\) of \([0-9]*\) images.*/\1/p' "$work/colmap.log")"
if [ -z "$registered" ] || [ "$registered" -lt 20 ]; then
  echo "FAILED: COLMAP registered ${registered:-no} images of 24 (at least 20 expected)"
  exit 1
fi
# Dataset::open on COLMAP's cameras, every buffer loaded, the depth fits reported.
"$glint" info "$work/colmap"
echo "PASSED: $registered of 24 images registered"
