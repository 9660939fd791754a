#!/usr/bin/env bash
# Installs the Debian 12 packages Glint builds and tests with; does nothing when all are present.
# With --fuzz, also the clang toolchain and libFuzzer that `make fuzz` builds with; with
# --colmap, Debian's colmap, which glint capture and the colmap_capture test use
# (the test is skipped without it, so `make test` does not need it); with --blender, Debian's
# Blender, which scripts/blender/ renders the Cycles validation scenes with.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libembree-dev libtbb-dev libopenexr-dev libtiff-dev libpng-dev libjpeg62-turbo-dev zlib1g-dev libstb-dev
  libtinygltf-dev nlohmann-json3-dev libcli11-dev libcpp-httplib-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  chromium  # the viewer's end-to-end test drives it headless (tests/web)
  ffmpeg    # glint render --path encodes its frames into an MP4
  openmpi-bin libopenmpi-dev  # training, rendering and synthesis over MPI (docs/cluster.md); the 2-rank tests
)
for option in "$@"; do
  case "$option" in
    --fuzz) packages+=(clang-14 libfuzzer-14-dev libclang-rt-14-dev) ;;  # make fuzz (docs/fuzzing.md)
    --colmap) packages+=(colmap) ;;  # structure from motion for real-capture-like tests
    --blender) packages+=(blender) ;;  # Cycles validation scenes (docs/blender-validation.md)
    *) echo "install-deps: unknown option $option (expected --fuzz, --colmap or --blender)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
