#!/usr/bin/env bash
# Unpacks the build carried in device-carry/ (scripts/pack-device-build.sh) on the GPU machine and sets LD_LIBRARY_PATH for it.
#
# Usage:  source scripts/device-unpack.sh [SCRATCH_DIR=/tmp/glint-device]   # exports the variables
#         scripts/device-unpack.sh [SCRATCH_DIR]                            # prints the export lines
# Afterwards the executables are at SCRATCH_DIR/build/... (e.g. $GLINT_DEVICE_DIR/build/glint) and
# their libraries at SCRATCH_DIR/lib.

# The work runs in a subshell so that set -euo pipefail and a failure's exit stay out of the
# shell that sources this file.
_glint_device_unpack() (
  set -euo pipefail
  die() { echo "device-unpack: $*" >&2; exit 1; }

  repo=$1
  scratch=${2:-/tmp/glint-device}
  carry="$repo/device-carry"

  [ -d "$carry" ] || die "no $carry folder: run scripts/pack-device-build.sh on the build machine and carry 'device-carry'"
  for f in bin.tar.gz libs.tar.gz; do
    [ -f "$carry/$f" ] || die "$carry/$f is missing: rerun scripts/pack-device-build.sh and carry the whole device-carry folder"
  done
  case "$scratch" in
    -*) die "'$scratch' is not a scratch folder (usage: scripts/device-unpack.sh [SCRATCH_DIR])" ;;
    /) die "refusing to unpack into /: name a scratch folder" ;;
    /*) ;;
    *) scratch="$PWD/$scratch" ;;  # the printed LD_LIBRARY_PATH must not depend on the cwd
  esac

  # Clear what an earlier unpack left, so that no stale executable or library is mixed in;
  # only the folders the tarballs create are removed, never the scratch folder as a whole.
  mkdir -p "$scratch"
  for top in lib $(tar -tzf "$carry/bin.tar.gz" | cut -d/ -f1 | sort -u); do
    [ -n "$top" ] && [ "$top" != . ] && [ "$top" != .. ] && rm -rf "${scratch:?}/$top"
  done
  for f in "$carry"/*.tar.gz; do
    tar -C "$scratch" -xzf "$f" || die "cannot unpack $f into $scratch"
  done
  [ -f "$carry/manifest.txt" ] && cp "$carry/manifest.txt" "$scratch/manifest.txt"

  # The executables were built from one commit; on a checkout of another they may not match
  # its tests and data.
  packed=$(sed -n 's/^commit: \([0-9a-f]*\).*/\1/p' "$carry/manifest.txt" 2>/dev/null || true)
  here=$(git -C "$repo" rev-parse HEAD 2>/dev/null || true)
  if [ -n "$packed" ] && [ -n "$here" ] && [ "$packed" != "$here" ]; then
    echo "device-unpack: warning: the build was packed at commit $packed but this checkout is at $here" >&2
  fi

  # Fail here, naming the library, rather than later with the loader's terse message.
  glint="$scratch/build/glint"
  # (Packed from another BUILD_DIR than build/, it lies elsewhere.)
  [ -x "$glint" ] || glint=$(find "$scratch" -path "$scratch/lib" -prune -o -type f -name glint -perm -u+x -print -quit)
  if [ -z "$glint" ]; then die "no glint executable in $carry/bin.tar.gz"; fi
  if command -v ldd >/dev/null; then
    missing=$(LD_LIBRARY_PATH="$scratch/lib" ldd "$glint" | awk '/not found/ { print $1 }' | tr '\n' ' ')
    [ -z "$missing" ] || die "$glint needs libraries that neither $carry/libs.tar.gz nor this system has: $missing"
  fi

  echo "device-unpack: unpacked $(tar -tzf "$carry/bin.tar.gz" | grep -vc '/$') executables and $(find "$scratch/lib" -type f | wc -l) libraries into $scratch" >&2
  echo "$scratch"
)

_glint_device_repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
if [ "${BASH_SOURCE[0]}" != "$0" ]; then
  # Sourced: export into the caller's shell. The carried libraries come first, ahead of any
  # CUDA paths already set, which stay.
  if _glint_device_dir=$(_glint_device_unpack "$_glint_device_repo" "$@"); then
    export GLINT_DEVICE_DIR="$_glint_device_dir"
    export LD_LIBRARY_PATH="$_glint_device_dir/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    echo "device-unpack: exported GLINT_DEVICE_DIR=$GLINT_DEVICE_DIR and LD_LIBRARY_PATH=$LD_LIBRARY_PATH" >&2
    unset _glint_device_dir _glint_device_repo
    unset -f _glint_device_unpack
  else
    unset _glint_device_dir _glint_device_repo
    unset -f _glint_device_unpack
    return 1
  fi
else
  set -euo pipefail
  case "${1:-}" in -h|--help) sed -n '2,8p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;; esac
  [ $# -le 1 ] || { echo "device-unpack: too many arguments (usage: scripts/device-unpack.sh [SCRATCH_DIR])" >&2; exit 1; }
  dir=$(_glint_device_unpack "$_glint_device_repo" "$@")
  # The ${LD_LIBRARY_PATH...} part is printed unexpanded so that, pasted or eval'd, the line
  # keeps whatever is set in that shell (CUDA paths, say).
  printf 'export GLINT_DEVICE_DIR=%q\n' "$dir"
  printf 'export LD_LIBRARY_PATH=%q${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}\n' "$dir/lib"
fi
