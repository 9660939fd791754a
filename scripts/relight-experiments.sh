#!/bin/bash
# Edits scored against each edited scene's own ground truth, with and without relighting and
# healing of the uncovered surface (README, "Edits that move shadows"): a built-in scene at
# 160x120, the default glint train, one object moved, duplicated or deleted by
# `glint synth --edits` and `glint eval --edits`, then the relighting's clamp, filter radius
# and ray count varied. Prints the README's three tables.
#   spheres: the red chrome sphere moved 0.5 m, duplicated 0.9 m away, or deleted
#   room:    the purple ball on the floor moved 0.5 m, duplicated 0.85 m away, or deleted
# Usage: scripts/relight-experiments.sh OUT [GLINT] [spheres|room]   (about 2.5 hours on 2
# cores; an OUT that already holds D, D_* and R, such as the last run's, skips the synthesis
# and training, about 40 minutes of it)
set -euo pipefail
out="${1:?usage: relight-experiments.sh OUT [GLINT] [spheres|room]}"
glint="$(realpath "${2:-build/glint}")"
scene="${3:-spheres}"
case "$scene" in
  spheres)
    pick='"selections": {"it": {"sphere": {"center": [-1.3, 0.6, 0.3], "radius": 0.65}}}'
    move='[0, 0, 0.5]' copy='[0.9, 0, 0.9]' ;;
  room)
    pick='"selections": {"it": {"sphere": {"center": [1.6, 0.35, -1.6], "radius": 0.37}}}'
    move='[-0.5, 0, 0]' copy='[-0.8, 0, 0.3]' ;;
  *) echo "relight-experiments: unknown scene $scene (spheres or room)" >&2; exit 2 ;;
esac
mkdir -p "$out"
cd "$out"
edits() { echo "{\"glint_edits\": 1, $pick, \"operations\": [$1]}"; }
edits "{\"op\": \"translate\", \"selection\": \"it\", \"offset\": $move}" > edits_move.json
edits "{\"op\": \"duplicate\", \"selection\": \"it\", \"offset\": $copy}" > edits_duplicate.json
edits '{"op": "delete", "selection": "it"}' > edits_delete.json
edits '{"op": "translate", "selection": "it", "offset": [0, 0, 0]}' > edits_null.json
S="--res 160x120 --spp 64 --test-spp 128 --test 10 --threads 2 --force"
[ -d D ] || "$glint" synth "builtin:$scene" -o D $S --train 40
for e in move duplicate delete; do
  [ -d "D_$e" ] || "$glint" synth "builtin:$scene" -o "D_$e" $S --train 1 --edits "edits_$e.json"
done
[ -f R/scene.ply ] || "$glint" train D -o R --threads 2 --force
E="--spp 64 --threads 2"
ev() { local name="$1" dataset="$2"; shift 2; "$glint" eval R --dataset "$dataset" $E "$@" -o "R/eval/$name.json"; }
ev unedited D
ev null_relight D --edits edits_null.json --no-heal
ev null_heal D --edits edits_null.json --heal
for e in move duplicate delete; do
  f=(--edits "edits_$e.json")
  ev "$e" "D_$e" "${f[@]}" --no-relight --no-heal
  ev "${e}_relight" "D_$e" "${f[@]}" --no-heal --relight-max-ratio 4
  ev "${e}_heal" "D_$e" "${f[@]}" --heal --relight-max-ratio 4
  ev "${e}_clamp16" "D_$e" "${f[@]}" --relight-filter 0
  ev "${e}_clamp64" "D_$e" "${f[@]}" --relight-filter 0 --relight-max-ratio 64
  ev "${e}_default" "D_$e" "${f[@]}"
  for radius in 0.5 1.5 2 3 4 6; do ev "${e}_filter$radius" "D_$e" "${f[@]}" --relight-filter "$radius"; done
  for rays in 16 32 128; do ev "${e}_rays$rays" "D_$e" "${f[@]}" --relight-rays "$rays"; done
done
python3 - <<'PY'
import json
def m(f):
    d = json.load(open('R/eval/' + f + '.json'))['mean']
    return [d[p]['psnr_tonemapped'] for p in ('diffuse', 'specular', 'final')]
u = m('unedited')
edits = ('move', 'duplicate', 'delete')
def row(cells, v):
    print('| ' + ' | '.join(cells) + ' | %.2f | %.2f | %.2f | %.2f | %.2f |' % (v[0], v[1], v[2], u[2] - v[2], u[0] - v[0]))
print('| edit | relighting (clamp) | healing | diffuse dB | specular dB | final dB | final drop | diffuse drop |')
print('| --- | --- | --- | --- | --- | --- | --- | --- |')
print('| none | - | - | %.2f | %.2f | %.2f | - | - |' % tuple(u))
row(('translate by 0', 'on (default)', 'off'), m('null_relight'))
row(('translate by 0', 'on (default)', 'on'), m('null_heal'))
for e in edits:
    for f, r, h in (('', 'off', 'off'), ('_relight', 'on (4)', 'off'), ('_heal', 'on (4)', 'on'),
                    ('_clamp16', 'on (16), no filter', 'on'), ('_clamp64', 'on (64), no filter', 'on'),
                    ('_default', 'on (16), filter 1: the default', 'on')):
        row((e, r, h), m(e + f))
print('\n| edit | filter radius | diffuse dB | specular dB | final dB | final drop | diffuse drop |')
print('| --- | --- | --- | --- | --- | --- | --- |')
for e in edits:
    for radius, f in (('0 (none)', '_clamp16'), ('0.5', '_filter0.5'), ('1 (the default)', '_default'),
                      ('1.5', '_filter1.5'), ('2', '_filter2'), ('3', '_filter3'), ('4', '_filter4'), ('6', '_filter6')):
        row((e, radius), m(e + f))
print('\n| rays | ' + ' | '.join(edits) + ' |  (final dB)')
print('| --- | --- | --- | --- |')
for rays, f in (('16', '_rays16'), ('32', '_rays32'), ('64 (the default)', '_default'), ('128', '_rays128')):
    print('| %s | ' % rays + ' | '.join('%.2f' % m(e + f)[2] for e in edits) + ' |')
PY
