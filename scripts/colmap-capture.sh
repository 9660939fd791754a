#!/usr/bin/env bash
# Reconstructs the cameras of a capture folder with COLMAP (CPU SIFT, exhaustive matching,
# incremental mapping) and writes a copy of the capture whose sparse/0 is COLMAP's, so that
# Glint trains from estimated cameras instead of true ones (docs/capture-format.md).
#
# Usage: scripts/colmap-capture.sh IN OUT [--no-intrinsics] [--threads N]
#   IN   a capture folder with images/ (priors/, capture.json and sparse/0 optional)
#   OUT  written anew: images/ and priors/ (hard links to IN's files, copies across file
#        systems), capture.json, sparse/0/*.txt from COLMAP, and colmap/ (its database,
#        binary models and logs). OUT is replaced only if an earlier run of this script
#        made it, so running twice gives the same folder.
# When IN has sparse/0/cameras.txt with a PINHOLE camera, its fx, fy, cx, cy start COLMAP's
# estimate (as EXIF focal lengths would for photographs; the mapper still refines the
# focal length); --no-intrinsics lets COLMAP guess them from the image size instead.
set -euo pipefail

usage() { echo "usage: $0 IN OUT [--no-intrinsics] [--threads N]" >&2; exit 2; }
fail() { echo "colmap-capture: $*" >&2; exit 1; }

[ $# -ge 2 ] || usage
in="${1%/}"
out="${2%/}"
shift 2
use_intrinsics=1
threads=-1
while [ $# -gt 0 ]; do
  case "$1" in
    --no-intrinsics) use_intrinsics=0 ;;
    --threads) [ $# -ge 2 ] || usage; threads="$2"; shift ;;
    *) usage ;;
  esac
  shift
done

command -v colmap >/dev/null || fail "colmap is not installed (scripts/install-deps.sh --colmap installs Debian's)"
[ -d "$in/images" ] || fail "$in/images: no such folder (IN must be a capture folder with images/)"
[ -n "$(ls -A "$in/images")" ] || fail "$in/images: the folder is empty"
marker=".colmap-capture"
if [ -e "$out" ] && [ ! -e "$out/$marker" ]; then
  fail "$out exists and was not written by this script; choose another OUT or remove it"
fi
mkdir -p "$(dirname "$out")"
out_parent="$(cd "$(dirname "$out")" && pwd -P)"
[ "$(cd "$in" && pwd -P)" != "$out_parent/$(basename "$out")" ] || fail "IN and OUT are the same folder"

# Without a display Qt (linked by Debian's colmap) must not look for one.
export QT_QPA_PLATFORM="${QT_QPA_PLATFORM:-offscreen}"

# Everything is built in a temporary folder beside OUT and moved into place at the end, so
# a failed run leaves the previous OUT (or nothing) behind.
work="$(mktemp -d "$out_parent/.colmap-capture.XXXXXX")"
trap 'rm -rf "$work"' EXIT
link_tree() { cp -al "$1" "$2" 2>/dev/null || cp -a "$1" "$2"; }
link_tree "$in/images" "$work/images"
[ -d "$in/priors" ] && link_tree "$in/priors" "$work/priors"
[ -f "$in/capture.json" ] && cp "$in/capture.json" "$work/capture.json"
mkdir -p "$work/colmap/sparse" "$work/sparse/0"
db="$work/colmap/database.db"
log="$work/colmap/log.txt"

intrinsics=()
cameras="$in/sparse/0/cameras.txt"
if [ "$use_intrinsics" = 1 ] && [ -f "$cameras" ]; then
  # First camera line: CAMERA_ID PINHOLE WIDTH HEIGHT fx fy cx cy.
  params="$(awk '!/^#/ && $2 == "PINHOLE" { print $5 "," $6 "," $7 "," $8; exit }' "$cameras")"
  if [ -n "$params" ]; then
    intrinsics=(--ImageReader.camera_params "$params")
    echo "colmap-capture: starting from the intrinsics of $cameras: fx,fy,cx,cy = $params"
  fi
fi

run() {  # run STEP colmap-arguments...: COLMAP's output goes to the log, shown on failure
  local step="$1"
  shift
  echo "colmap-capture: $step"
  if ! colmap "$@" >>"$log" 2>&1; then
    tail -n 30 "$log" >&2
    fail "colmap $1 failed (the end of its log is above)"
  fi
}
start=$(date +%s)
run "extracting SIFT features" feature_extractor --database_path "$db" --image_path "$work/images" \
  --ImageReader.camera_model PINHOLE --ImageReader.single_camera 1 "${intrinsics[@]}" \
  --SiftExtraction.use_gpu 0 --SiftExtraction.num_threads "$threads"
run "matching every pair of images" exhaustive_matcher --database_path "$db" \
  --SiftMatching.use_gpu 0 --SiftMatching.num_threads "$threads"
run "mapping (incremental structure from motion)" mapper --database_path "$db" --image_path "$work/images" \
  --output_path "$work/colmap/sparse" --Mapper.num_threads "$threads"

# The mapper may split the scene into several models (sparse/0, sparse/1, ...): keep the
# one that registered the most images.
best=""
best_count=0
for model in "$work"/colmap/sparse/*/; do
  [ -f "$model/images.bin" ] || continue
  count="$(colmap model_analyzer --path "$model" 2>&1 | sed -n 's/.*Registered images: *\([0-9]*\).*/\1/p')"
  if [ -n "$count" ] && [ "$count" -gt "$best_count" ]; then best="$model"; best_count="$count"; fi
done
if [ -z "$best" ]; then
  tail -n 30 "$log" >&2
  fail "COLMAP registered no images: the images need more texture or overlap"
fi
run "writing the model as text" model_converter --input_path "$best" --output_path "$work/sparse/0" --output_type TXT
stats="$(colmap model_analyzer --path "$best" 2>&1)"
error="$(printf '%s\n' "$stats" | sed -n 's/.*Mean reprojection error: *\([0-9.]*\).*/\1/p')"
points="$(printf '%s\n' "$stats" | sed -n 's/.*Points: *\([0-9]*\).*/\1/p')"
total="$(find "$work/images" -type f | wc -l)"
models="$(find "$work/colmap/sparse" -mindepth 1 -maxdepth 1 -type d | wc -l)"
touch "$work/$marker"

rm -rf "$out"
mv "$work" "$out"
trap - EXIT
echo "colmap-capture: registered $best_count of $total images in $models model(s), $points points," \
  "mean reprojection error $error px, in $(( $(date +%s) - start )) s"
[ "$best_count" -eq "$total" ] || echo "colmap-capture: warning: $(( total - best_count )) images have no camera and are left out of training"
echo "colmap-capture: wrote $out (sparse/0 is COLMAP's model in text form)"
