#!/bin/bash
# Edits of builtin:room scored against each edited scene's own ground truth, with and without
# relighting and healing (README, "Edits that move shadows"): the purple ball on the floor
# moved 0.5 m, duplicated 0.85 m away or deleted, 160x120, the default glint train.
# Usage: scripts/relight-room-experiments.sh OUT [GLINT]   (about 45 minutes on 2 cores)
set -euo pipefail
out="${1:?usage: relight-room-experiments.sh OUT [GLINT]}"
G="$(realpath "${2:-build/glint}")"
mkdir -p "$out"
cd "$out"
ball='"selections": {"ball": {"sphere": {"center": [1.6, 0.35, -1.6], "radius": 0.37}}}'
echo "{\"glint_edits\": 1, $ball, \"operations\": [{\"op\": \"translate\", \"selection\": \"ball\", \"offset\": [-0.5, 0, 0]}]}" > edits_move.json
echo "{\"glint_edits\": 1, $ball, \"operations\": [{\"op\": \"duplicate\", \"selection\": \"ball\", \"offset\": [-0.8, 0, 0.3]}]}" > edits_duplicate.json
echo "{\"glint_edits\": 1, $ball, \"operations\": [{\"op\": \"delete\", \"selection\": \"ball\"}]}" > edits_delete.json
echo "{\"glint_edits\": 1, $ball, \"operations\": [{\"op\": \"translate\", \"selection\": \"ball\", \"offset\": [0, 0, 0]}]}" > edits_null.json
S="--res 160x120 --spp 64 --test-spp 128 --test 10 --threads 2 --force"
[ -d D ] || $G synth builtin:room -o D $S --train 40 > synth.log 2>&1
for e in move duplicate delete; do
  [ -d "D_$e" ] || $G synth builtin:room -o "D_$e" $S --train 1 --edits "edits_$e.json" > synth_$e.log 2>&1
done
[ -f R/scene.ply ] || $G train D -o R --threads 2 --force > train.log 2>&1
E="--spp 64 --threads 2"
mkdir -p ev
$G eval R --dataset D $E -o ev/unedited.json > ev_unedited.log 2>&1
$G eval R --dataset D $E --edits edits_null.json -o ev/null.json > ev_null.log 2>&1
for e in move duplicate delete; do
  $G eval R --dataset "D_$e" $E --edits "edits_$e.json" -o "ev/${e}_default.json" > ev_$e.log 2>&1
  $G eval R --dataset "D_$e" $E --edits "edits_$e.json" --no-relight --no-heal -o "ev/$e.json" > ev_${e}_off.log 2>&1
done
python3 - <<'PY'
import json
def m(f):
    d = json.load(open('ev/' + f + '.json'))['mean']
    return [d[p]['psnr_tonemapped'] for p in ('diffuse', 'specular', 'final')]
u = m('unedited')
print('| edit | relighting + healing | final dB | final drop | diffuse drop |')
print('| --- | --- | --- | --- | --- |')
print('| none | - | %.2f | - | - |' % u[2])
rows = [('translate by 0', 'null', 'on')]
for e in ('move', 'duplicate', 'delete'):
    rows += [(e, e, 'off'), (e, e + '_default', 'on (default)')]
for name, f, r in rows:
    v = m(f)
    print('| %s | %s | %.2f | %.2f | %.2f |' % (name, r, v[2], u[2] - v[2], u[0] - v[0]))
PY
