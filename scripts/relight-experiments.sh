#!/bin/bash
# Edits scored against each edited scene's own ground truth, with and without relighting and
# healing of the uncovered surface (README, "Edits that move shadows"): builtin:spheres at
# 160x120, the default glint train, the red sphere moved, duplicated or deleted by
# `glint synth --edits` and `glint eval --edits`.
# Usage: scripts/relight-experiments.sh OUT [GLINT]   (about 60 minutes on 2 cores; an OUT that
# already holds D, D_* and R, such as the last run's, skips the synthesis and training)
set -euo pipefail
out="${1:?usage: relight-experiments.sh OUT [GLINT]}"
glint="$(realpath "${2:-build/glint}")"
mkdir -p "$out"
cd "$out"
red='"selections": {"red": {"sphere": {"center": [-1.3, 0.6, 0.3], "radius": 0.65}}}'
echo "{\"glint_edits\": 1, $red, \"operations\": [{\"op\": \"translate\", \"selection\": \"red\", \"offset\": [0, 0, 0.5]}]}" > edits_move.json
echo "{\"glint_edits\": 1, $red, \"operations\": [{\"op\": \"duplicate\", \"selection\": \"red\", \"offset\": [0.9, 0, 0.9]}]}" > edits_duplicate.json
echo "{\"glint_edits\": 1, $red, \"operations\": [{\"op\": \"delete\", \"selection\": \"red\"}]}" > edits_delete.json
echo "{\"glint_edits\": 1, $red, \"operations\": [{\"op\": \"translate\", \"selection\": \"red\", \"offset\": [0, 0, 0]}]}" > edits_null.json
S="--res 160x120 --spp 64 --test-spp 128 --test 10 --threads 2 --force"
[ -d D ] || "$glint" synth builtin:spheres -o D $S --train 40
for e in move duplicate delete; do
  [ -d "D_$e" ] || "$glint" synth builtin:spheres -o "D_$e" $S --train 1 --edits "edits_$e.json"
done
[ -f R/scene.ply ] || "$glint" train D -o R --threads 2 --force
E="--spp 64 --threads 2"
"$glint" eval R --dataset D $E -o R/eval/unedited.json
"$glint" eval R --dataset D $E --edits edits_null.json --no-heal -o R/eval/null_relight.json
"$glint" eval R --dataset D $E --edits edits_null.json --heal -o R/eval/null_heal.json
for e in move duplicate delete; do
  "$glint" eval R --dataset "D_$e" $E --edits "edits_$e.json" --no-relight --no-heal -o "R/eval/$e.json"
  "$glint" eval R --dataset "D_$e" $E --edits "edits_$e.json" --no-heal --relight-max-ratio 4 \
    -o "R/eval/${e}_relight.json"
  "$glint" eval R --dataset "D_$e" $E --edits "edits_$e.json" --heal --relight-max-ratio 4 -o "R/eval/${e}_heal.json"
  "$glint" eval R --dataset "D_$e" $E --edits "edits_$e.json" --relight-filter 0 -o "R/eval/${e}_clamp16.json"
  "$glint" eval R --dataset "D_$e" $E --edits "edits_$e.json" --relight-filter 0 --relight-max-ratio 64 \
    -o "R/eval/${e}_clamp64.json"
  "$glint" eval R --dataset "D_$e" $E --edits "edits_$e.json" -o "R/eval/${e}_default.json"
done
python3 - <<'PY'
import json
def m(f):
    d = json.load(open('R/eval/' + f + '.json'))['mean']
    return [d[p]['psnr_tonemapped'] for p in ('diffuse', 'specular', 'final')]
u = m('unedited')
print('| edit | relighting (clamp) | healing | diffuse dB | specular dB | final dB | final drop | diffuse drop |')
print('| --- | --- | --- | --- | --- | --- | --- | --- |')
print('| none | - | - | %.2f | %.2f | %.2f | - | - |' % tuple(u))
rows = [('translate by 0', 'null_relight', 'on (default)', 'off'), ('translate by 0', 'null_heal', 'on (default)', 'on')]
for e in ('move', 'duplicate', 'delete'):
    rows += [(e, e, 'off', 'off'), (e, e + '_relight', 'on (4)', 'off'), (e, e + '_heal', 'on (4)', 'on'),
             (e, e + '_clamp16', 'on (16), no filter', 'on'), (e, e + '_clamp64', 'on (64), no filter', 'on'),
             (e, e + '_default', 'on (16), filter 1: the default', 'on')]
for name, f, r, h in rows:
    v = m(f)
    print('| %s | %s | %s | %.2f | %.2f | %.2f | %.2f | %.2f |' % (name, r, h, v[0], v[1], v[2], u[2] - v[2], u[0] - v[0]))
PY
