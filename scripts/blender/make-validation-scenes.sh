#!/usr/bin/env bash
# Renders both Blender Cycles validation scenes into OUT_ROOT and checks them with `glint info`.
# Usage: scripts/blender/make-validation-scenes.sh OUT_ROOT
# Full settings (docs/blender-validation.md): 160x120, 100 training views at 256 spp, 20 test
# views at 512 spp, plus the seed-vs-seed noise check. About 50 minutes on two idle cores.
# Environment: SCENES ("spheres_room mirror_room"), TRAIN_VIEWS (100), TEST_SPP (512).
set -euo pipefail

if [ $# -ne 1 ]; then
  echo "usage: $0 OUT_ROOT" >&2
  exit 2
fi
if ! command -v blender > /dev/null; then
  echo "make-validation-scenes: blender not found; install with scripts/install-deps.sh --blender" >&2
  exit 1
fi

here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
out_root="$1"
mkdir -p "$out_root"

scenes="${SCENES:-spheres_room mirror_room}"
for scene in $scenes; do
  echo "make-validation-scenes: rendering $scene into $out_root/$scene"
  blender -b --factory-startup --python-exit-code 1 -P "$here/render_dataset.py" -- \
    --scene "$scene" --out "$out_root/$scene" --res 160x120 \
    --train-views "${TRAIN_VIEWS:-100}" --test-views 20 --train-spp 256 --test-spp "${TEST_SPP:-512}" --seed 0 \
    --noise-check
done

# The renderer we validate reads the datasets back; skip quietly when it is not built.
if [ -x "$repo/build/glint" ]; then
  for scene in $scenes; do
    "$repo/build/glint" info "$out_root/$scene"
  done
fi
