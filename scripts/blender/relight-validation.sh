#!/bin/bash
# Edits scored against Blender's own renders of the edited scene (README, "Edits that move
# shadows"). spheres_room: the chrome sphere moved 0.3 m, duplicated, or deleted.
# mirror_room: the copper pot moved 25 cm across the table (its reflection in the mirror
# wall moves too), duplicated onto the floor in front of the table, or deleted. Cycles
# renders the test views of each edited scene (the unedited dataset's cameras:
# render_dataset.py --edit --test-only), and `glint eval --edits` scores a run trained on
# the unedited dataset with relighting and healing (the default) and without.
# Usage: scripts/blender/relight-validation.sh DATASET RUN OUT [GLINT]
#   DATASET: the unedited spheres_room or mirror_room dataset (render_dataset.py
#   --train-views 60 --test-views 20 --test-spp 256 --seed 0, as docs/blender-validation.md
#   makes it; the scene is read from its render_settings.json)
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

scene="$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['scene'])" "$dataset/render_settings.json")"
case "$scene" in
  spheres_room)
    # The chrome sphere (centre (-0.9, 0.3, 0.5), radius 0.5, on the floor): a box that stops
    # 1 cm above the floor, grown along connected Gaussians of its material to take the
    # contact cap and never the floor.
    object=chrome tolerance=0.2
    pick='"box": {"min": [-1.45, -0.25, 0.01], "max": [-0.35, 0.85, 1.05]}'
    move=0.3,0,0 copy=2.1,-0.8,0
    object_region=-1.45,-0.25,0.02,-0.35,0.85,1.05
    # Where the copy stands, for eval --region (the pixels of the copy scored apart).
    copy_region=0.65,-1.05,0.02,1.75,0.05,1.05 ;;
  mirror_room)
    # The copper pot (radius 0.3 m, 0.33 m tall, centre of its base (0.25, 1.3, 0.78) on the
    # table top): a box that stops 1 cm above the table, grown along the pot's material. The
    # trained copper and glossy table differ little: a tolerance of 0.2 or 0.1 grew the
    # selection over the whole table top (1,741 and 1,300 Gaussians on a 9,143-Gaussian run,
    # against 698 in the box); 0.05 adds only the pot's base ring (742).
    object=copper_pot tolerance=0.05
    pick='"box": {"min": [-0.07, 0.98, 0.79], "max": [0.57, 1.62, 1.13]}'
    move=0.2,0.15,0 copy=0,-1.0,-0.78
    object_region=-0.07,0.98,0.79,0.57,1.62,1.13
    copy_region=-0.07,-0.02,0.0,0.57,0.62,0.35 ;;
  *) echo "relight-validation: no edits defined for scene $scene" >&2; exit 1 ;;
esac
pick="\"selections\": {\"$object\": {$pick, \"grow\": {\"distance\": 0.05, \"tolerance\": $tolerance}}}"
edits() { echo "{\"glint_edits\": 1, $pick, \"operations\": [$1]}"; }
edits "{\"op\": \"translate\", \"selection\": \"$object\", \"offset\": [$move]}" > edits_move.json
edits "{\"op\": \"duplicate\", \"selection\": \"$object\", \"offset\": [$copy]}" > edits_duplicate.json
edits "{\"op\": \"delete\", \"selection\": \"$object\"}" > edits_delete.json
edits "{\"op\": \"translate\", \"selection\": \"$object\", \"offset\": [0, 0, 0]}" > edits_null.json
declare -A blender_edit=([move]="translate:$object:$move" [duplicate]="duplicate:$object:$copy"
                         [delete]="delete:$object")
for e in move duplicate delete; do
  [ -f "D_$e/transforms_test.json" ] && [ -f "D_$e/preview.png" ] && continue
  blender -b --factory-startup --python-exit-code 1 -P "$here/render_dataset.py" -- --scene "$scene" \
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
# With the pixels of the original object and of its copy scored apart (--region): where the
# duplication's drop lies.
"$glint" eval "$run" --dataset "$dataset" $E --region=$object_region -o eval/unedited.json
"$glint" eval "$run" --dataset "$dataset" $E --edits edits_null.json -o eval/null.json
for e in move duplicate delete; do
  "$glint" eval "$run" --dataset "D_$e" $E --edits "edits_$e.json" --no-relight --no-heal -o "eval/$e.json"
  region=()
  [ "$e" = duplicate ] && region=(--region=$copy_region)
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
