#!/bin/bash
# Edits scored against Blender's own renders of the edited scene (README, "Edits that move
# shadows"): the chrome sphere of the Blender spheres_room moved 0.3 m, duplicated, or
# deleted. Cycles renders the test views of each edited scene (the unedited dataset's
# cameras: render_dataset.py --edit --test-only), and `glint eval --edits` scores a run
# trained on the unedited dataset with relighting and healing (the default) and without.
# Usage: scripts/blender/relight-validation.sh DATASET RUN OUT [GLINT]
#   DATASET: the unedited spheres_room dataset (render_dataset.py --train-views 60
#   --test-views 20 --test-spp 256 --seed 0, as docs/blender-validation.md makes it)
#   RUN: a glint train run on it. Needs Blender (scripts/install-deps.sh --blender); about
#   30 minutes on 2 cores.
set -euo pipefail
dataset="$(realpath "${1:?usage: relight-validation.sh DATASET RUN OUT [GLINT]}")"
run="$(realpath "${2:?usage: relight-validation.sh DATASET RUN OUT [GLINT]}")"
out="${3:?usage: relight-validation.sh DATASET RUN OUT [GLINT]}"
glint="$(realpath "${4:-build/glint}")"
here="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$out"
out="$(realpath "$out")"
cd "$out"

# The chrome sphere (centre (-0.9, 0.3, 0.5), radius 0.5, on the floor): a box that stops
# 1 cm above the floor, grown along connected Gaussians of its material to take the contact
# cap and never the floor.
pick='"selections": {"chrome": {"box": {"min": [-1.45, -0.25, 0.01], "max": [-0.35, 0.85, 1.05]},
                                 "grow": {"distance": 0.05, "tolerance": 0.2}}}'
edits() { echo "{\"glint_edits\": 1, $pick, \"operations\": [$1]}"; }
edits '{"op": "translate", "selection": "chrome", "offset": [0.3, 0, 0]}' > edits_move.json
edits '{"op": "duplicate", "selection": "chrome", "offset": [2.1, -0.8, 0]}' > edits_duplicate.json
edits '{"op": "delete", "selection": "chrome"}' > edits_delete.json
edits '{"op": "translate", "selection": "chrome", "offset": [0, 0, 0]}' > edits_null.json
declare -A blender_edit=([move]="translate:chrome:0.3,0,0" [duplicate]="duplicate:chrome:2.1,-0.8,0"
                         [delete]="delete:chrome")
for e in move duplicate delete; do
  [ -f "D_$e/transforms_test.json" ] && [ -f "D_$e/preview.png" ] && continue
  blender -b --factory-startup --python-exit-code 1 -P "$here/render_dataset.py" -- --scene spheres_room \
    --out "D_$e" --res 160x120 --train-views 60 --test-views 20 --test-spp 256 --seed 0 \
    --edit "${blender_edit[$e]}" --test-only > "blender_$e.log" 2>&1
done
# The edited datasets' cameras must be the unedited one's.
for e in move duplicate delete; do
  cmp -s <(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['frames'])" "$dataset/transforms_test.json") \
         <(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['frames'])" "D_$e/transforms_test.json") ||
    { echo "relight-validation: D_$e has other test cameras than $dataset" >&2; exit 1; }
done

E="--spp 64 --threads 2"
mkdir -p eval
# With the pixels of the original sphere and of its copy scored apart (--region): where the
# duplication's drop lies.
"$glint" eval "$run" --dataset "$dataset" $E --region=-1.45,-0.25,0.02,-0.35,0.85,1.05 -o eval/unedited.json
"$glint" eval "$run" --dataset "$dataset" $E --edits edits_null.json -o eval/null.json
for e in move duplicate delete; do
  "$glint" eval "$run" --dataset "D_$e" $E --edits "edits_$e.json" --no-relight --no-heal -o "eval/$e.json"
  region=()
  [ "$e" = duplicate ] && region=(--region=0.65,-1.05,0.02,1.75,0.05,1.05)
  "$glint" eval "$run" --dataset "D_$e" $E --edits "edits_$e.json" "${region[@]}" -o "eval/${e}_default.json"
done
python3 - <<'PY'
import json
def m(f):
    d = json.load(open('eval/' + f + '.json'))['mean']
    return [d[p]['psnr_tonemapped'] for p in ('diffuse', 'specular', 'final')]
u = m('unedited')
print('| edit | relighting + healing | diffuse dB | specular dB | final dB | final drop | diffuse drop |')
print('| --- | --- | --- | --- | --- | --- | --- |')
print('| none | - | %.2f | %.2f | %.2f | - | - |' % tuple(u))
v = m('null')
print('| translate by 0 | on (default) | %.2f | %.2f | %.2f | %.2f | %.2f |' % (v[0], v[1], v[2], u[2] - v[2], u[0] - v[0]))
for e in ('move', 'duplicate', 'delete'):
    for f, r in ((e, 'off'), (e + '_default', 'on (default)')):
        v = m(f)
        print('| %s | %s | %.2f | %.2f | %.2f | %.2f | %.2f |' % (e, r, v[0], v[1], v[2], u[2] - v[2], u[0] - v[0]))
PY
