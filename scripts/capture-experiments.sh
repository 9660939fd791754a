#!/usr/bin/env bash
# The real-capture figures of the README: builtin:gallery rendered as a capture (JPEG
# photographs, priors, true cameras), its cameras re-estimated by COLMAP, its priors
# degraded like a network's, and Glint trained and evaluated on
#   (a) exact buffers, true cameras;  (b) exact buffers, COLMAP cameras;
#   (c) degraded buffers, COLMAP cameras;  (d) (c) with each buffer kind left out in turn.
# Every run is scored by `glint eval` on the held-out views against the exact buffers.
#
# Usage: scripts/capture-experiments.sh [OUT]   (default out/capture-experiments)
# Environment: GLINT (build/glint), RES (320x240), VIEWS (120), SPP (64), TEST_SPP (256),
# ITERS (training steps; empty: glint train's default), EVAL_SPP (64), ABLATIONS
# ("diffuse specular normal depth roughness f0"; empty to skip (d)).
set -euo pipefail

glint="${GLINT:-build/glint}"
out="${1:-out/capture-experiments}"
res="${RES:-320x240}"
views="${VIEWS:-120}"
spp="${SPP:-64}"
test_spp="${TEST_SPP:-256}"
eval_spp="${EVAL_SPP:-64}"
ablations="${ABLATIONS-diffuse specular normal depth roughness f0}"
iters=()
[ -n "${ITERS:-}" ] && iters=(--iters "$ITERS")
here="$(cd "$(dirname "$0")" && pwd)"

[ -x "$glint" ] || { echo "capture-experiments: $glint not found (make build first)" >&2; exit 1; }
command -v colmap >/dev/null || { echo "capture-experiments: needs colmap (scripts/install-deps.sh --colmap)" >&2; exit 1; }
mkdir -p "$out"

# 1. The scene as photographs with exact and with degraded priors (the same images).
for kind in exact degraded; do
  if [ ! -f "$out/$kind/capture.json" ]; then
    degrade=none
    [ "$kind" = degraded ] && degrade=network
    "$glint" synth builtin:gallery -o "$out/$kind" --layout capture --res "$res" --train "$views" --spp "$spp" \
      --test-spp "$test_spp" --degrade "$degrade" --force
  fi
done

# 2. COLMAP's cameras for the photographs, shared by (b), (c) and (d).
[ -f "$out/exact_colmap/sparse/0/cameras.bin" ] || "$glint" capture "$out/exact" -o "$out/exact_colmap" --force
# The degraded priors with COLMAP's model (hard links: the files are the same).
make_variant() {  # make_variant NAME PRIORS_FROM [KIND_TO_LEAVE_OUT]
  local dir="$out/$1"
  rm -rf "$dir"
  mkdir -p "$dir/sparse"
  cp -al "$out/exact/images" "$dir/images"
  cp -al "$out/$2/priors" "$dir/priors"
  cp "$out/$2/capture.json" "$dir/capture.json"
  cp -al "$out/exact_colmap/sparse/0" "$dir/sparse/0"
  if [ -n "${3:-}" ]; then
    rm -rf "$dir/priors/$3"
    [ "$3" = f0 ] && rm -rf "$dir/priors/metalness"
  fi
  return 0
}
make_variant degraded_colmap degraded
for kind in $ablations; do make_variant "degraded_colmap_no_$kind" degraded "$kind"; done

# 3. Train and evaluate. Scores are against the exact buffers of the same cameras.
train_and_eval() {  # train_and_eval RUN DATASET TRUTH [TRAIN FLAGS...]
  local run="$out/runs/$1"
  if [ ! -f "$run/eval/metrics.json" ]; then
    "$glint" train "$2" -o "$run" "${iters[@]}" "${@:4}" --force
    "$glint" eval "$run" --dataset "$3" --spp "$eval_spp"
  fi
}
mkdir -p "$out/runs"
# Glint's defaults as a config file: without one, `glint train` gives a capture of predicted
# buffers the real-capture setting by itself, and (c) and (d) measure the defaults.
echo '{}' > "$out/defaults.json"
train_and_eval a_exact_true "$out/exact" "$out/exact"
train_and_eval b_exact_colmap "$out/exact_colmap" "$out/exact_colmap"
train_and_eval c_degraded_colmap "$out/degraded_colmap" "$out/exact_colmap" --config "$out/defaults.json"
# (c) with the paper's setting for predicted buffers (no depth loss, specular weight 0.01).
train_and_eval c_degraded_colmap_preset "$out/degraded_colmap" "$out/exact_colmap" \
  --config "$here/real-capture-train.json"
for kind in $ablations; do
  train_and_eval "d_no_$kind" "$out/degraded_colmap_no_$kind" "$out/exact_colmap" --config "$out/defaults.json"
done

# 4. The table: 8-bit tonemapped PSNR of diffuse, specular and final on the held-out views.
echo
printf "%-28s %9s %9s %9s\n" "run" "diffuse" "specular" "final"
for metrics in "$out"/runs/*/eval/metrics.json; do
  run="$(basename "$(dirname "$(dirname "$metrics")")")"
  python3 - "$metrics" "$run" <<'EOF'
import json, sys
m = json.load(open(sys.argv[1]))["mean"]
f = lambda p: "-" if m[p]["psnr_tonemapped"] is None else "%.2f" % m[p]["psnr_tonemapped"]
print("%-28s %9s %9s %9s" % (sys.argv[2], f("diffuse"), f("specular"), f("final")))
EOF
done
