#!/usr/bin/env bash
# Issue 44's levers under COLMAP's cameras: builtin:gallery (textured enough for COLMAP at
# 160x120, which builtin:room is not) rendered as captures of the same photographs with exact
# and predicted-looking priors, its cameras re-estimated by COLMAP, and Glint trained with
# the real-capture preset and with the depth loss back (through the band) on true and on
# COLMAP's cameras. Each run is scored by `glint eval --breakdown` on the held-out views
# against the exact buffers seen from the same cameras (8-bit tonemapped PSNR).
#
# Usage: scripts/colmap-prior-experiments.sh [OUT]   (default out/colmap-prior-experiments)
# Environment: GLINT (build/glint), ITERS (8000), RES (160x120), VIEWS (120, every 6th held
# out), EVAL_SPP (16), RUNS (default all: see `runs` below; a run is KIND_CAMERAS_SETTING).
set -euo pipefail

glint="${GLINT:-build/glint}"
out="${1:-out/colmap-prior-experiments}"
iters="${ITERS:-8000}"
res="${RES:-160x120}"
views="${VIEWS:-120}"
here="$(cd "$(dirname "$0")" && pwd)"
[ -x "$glint" ] || { echo "colmap-prior-experiments: $glint not found (make build first)" >&2; exit 1; }
command -v colmap >/dev/null || { echo "colmap-prior-experiments: needs colmap (scripts/install-deps.sh --colmap)" >&2; exit 1; }
mkdir -p "$out/runs" "$out/configs"

# 1. The captures (the same photographs and sparse points: same seed), COLMAP's model of the
# exact one's photographs, and each prior set with that model (hard links).
make_capture() {  # make_capture KIND
  [ -f "$out/$1/capture.json" ] || "$glint" synth builtin:gallery -o "$out/$1" --layout capture --res "$res" \
    --train "$views" --holdout 6 --spp 32 --test-spp 64 --degrade "$([ "$1" = exact ] && echo none || echo "$1")" --force
}
make_colmap_variant() {  # make_colmap_variant KIND
  local dir="$out/${1}_colmap"
  [ -f "$dir/capture.json" ] && return 0
  make_capture "$1"
  rm -rf "$dir"
  mkdir -p "$dir/sparse"
  cp -al "$out/exact/images" "$dir/images"
  cp -al "$out/$1/priors" "$dir/priors"
  cp "$out/$1/capture.json" "$dir/capture.json"
  cp -al "$out/exact_colmap/sparse/0" "$dir/sparse/0"
}
make_capture exact
[ -f "$out/exact_colmap/sparse/0/cameras.bin" ] || "$glint" capture "$out/exact" -o "$out/exact_colmap" --force

# 2. The settings: the preset (scripts/real-capture-train.json), the preset with the depth
# loss back through the band (and with it only where 2 of 8 neighbouring views agree within
# 2%: train/depth_consistency.h, in the loss alone and in the initialisation too), and the
# best setting of the true-camera runs on builtin:room (scripts/prior-experiments.sh,
# docs/captures.md).
cp "$here/real-capture-train.json" "$out/configs/preset.json"
echo '{"bounces": 2, "loss": {"depth_band": 0.1, "specular": 0.01}}' > "$out/configs/preset_band.json"
echo '{"bounces": 2, "loss": {"depth_band": 0.1, "specular": 0.01, "depth_consistency": 0.02}}' \
  > "$out/configs/preset_band_consistent.json"
# The same with the dense initialisation leaving out the untrusted depth too.
echo '{"bounces": 2, "init": {"consistent_depth_only": true}, "loss": {"depth_band": 0.1, "specular": 0.01, "depth_consistency": 0.02}}' \
  > "$out/configs/preset_band_consistent_init.json"
# Camera refinement (train/camera_refinement.h): every eighth of the run, up to three quarters.
echo "{\"bounces\": 2, \"loss\": {\"depth\": 0, \"specular\": 0.01}, \"cameras\": {\"refine_every\": $((iters / 8))}}" \
  > "$out/configs/preset_refine.json"
echo "{\"bounces\": 2, \"loss\": {\"depth_band\": 0.1, \"specular\": 0.01, \"depth_consistency\": 0.02}, \"cameras\": {\"refine_every\": $((iters / 8))}}" \
  > "$out/configs/preset_band_consistent_refine.json"
# The preset with the camera-independent levers of the true-camera runs: the photograph term
# at 3 and, on the monocular kind (a metalness prior), the tint option, alone and together.
echo '{"bounces": 2, "loss": {"depth": 0.0, "specular": 0.01, "photograph": 3.0}}' > "$out/configs/preset_photo3.json"
echo '{"bounces": 2, "f0_tint_from_reflections": true, "loss": {"depth": 0.0, "specular": 0.01, "f0_from_specular": 1.0, "f0_tint_prior": 0.1}}' \
  > "$out/configs/preset_tint.json"
sed 's/"f0_tint_prior": 0.1}/"f0_tint_prior": 0.1, "photograph": 3.0}/' "$out/configs/preset_tint.json" \
  > "$out/configs/preset_tint_photo3.json"
echo "{\"roughness_shift_invariant\": true, \"loss\": {\"normal\": 2.5, \"depth_band\": 0.1}, \"lr\": {\"normal_final\": 0.000025, \"normal_decay_steps\": $iters}}" \
  > "$out/configs/best.json"

train_and_eval() {  # train_and_eval RUN CAPTURE TRUTH CONFIG
  local run="$out/runs/$1"
  if [ ! -f "$run/eval/metrics.json" ]; then
    "$glint" train "$out/$2" -o "$run" --holdout 6 --iters "$iters" --config "$out/configs/$4.json" --force
    "$glint" eval "$run" --dataset "$out/$3" --spp "${EVAL_SPP:-16}" --bounces 4 --breakdown
  fi
}
runs="${RUNS:-monocular_colmap_preset monocular_colmap_best monocular_colmap_preset_band
  monocular_true_preset monocular_true_preset_band network_colmap_preset network_colmap_preset_band
  monocular_colmap_preset_band_consistent network_colmap_preset_band_consistent monocular_true_preset_band_consistent
  monocular_colmap_preset_band_consistent_init monocular_colmap_preset_refine
  monocular_colmap_preset_band_consistent_refine monocular_colmap_preset_tint_photo3
  network_colmap_preset_photo3 monocular_colmap_preset_tint monocular_colmap_preset_photo3}"
for name in $runs; do
  kind="${name%%_*}"
  rest="${name#*_}"
  cameras="${rest%%_*}"
  setting="${rest#*_}"
  if [ "$cameras" = colmap ]; then
    make_colmap_variant "$kind"
    train_and_eval "$name" "${kind}_colmap" exact_colmap "$setting"
  else
    make_capture "$kind"
    train_and_eval "$name" "$kind" exact "$setting"
  fi
done

# 3. The table.
echo
printf "%-32s %8s %8s %8s %8s %8s %8s %8s %8s\n" run diffuse specular final depth normal flat glossy curved
for metrics in "$out"/runs/*/eval/metrics.json; do
  python3 - "$metrics" <<'EOF'
import json, os, sys
m = json.load(open(sys.argv[1]))
a, b = m["mean"], m.get("breakdown", {})
f = lambda v: "-" if v is None else "%.2f" % v
s = lambda k: f(b.get(k, {}).get("specular_psnr_tonemapped"))
run = os.path.basename(os.path.dirname(os.path.dirname(sys.argv[1])))
print("%-32s %8s %8s %8s %8s %8s %8s %8s %8s" % (run, f(a["diffuse"]["psnr_tonemapped"]), f(a["specular"]["psnr_tonemapped"]),
      f(a["final"]["psnr_tonemapped"]), f(a.get("depth_rmse")), f(a.get("normal_angle_deg")),
      s("flat mirror"), s("glossy"), s("curved mirror")))
EOF
done
