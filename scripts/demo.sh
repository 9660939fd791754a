#!/usr/bin/env bash
# The demo of `make demo`: generates the built-in spheres scene, checks it, and writes a
# contact sheet of its buffers. Outputs go to out/demo/ (the demo's own folder).
set -euo pipefail
build="${1:-build}"
glint="$build/glint"
out="out/demo"
mkdir -p "$out"

echo "== 1/3 glint synth: path-tracing builtin:spheres (100 train + 20 test views, 160x120, 64 spp)"
"$glint" synth builtin:spheres -o "$out/spheres" --res 160x120 --spp 64 --force

echo "== 2/3 glint info: validating the dataset"
"$glint" info "$out/spheres"

echo "== 3/3 glint sheet: contact sheets of the train and test buffers"
"$glint" sheet "$out/spheres" -o "$out/spheres_train_sheet.png" --rows 4
"$glint" sheet "$out/spheres" --split test -o "$out/spheres_test_sheet.png" --rows 3

echo
echo "Done. Dataset: $out/spheres   Contact sheets: $out/spheres_train_sheet.png, $out/spheres_test_sheet.png"
