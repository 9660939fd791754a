#!/usr/bin/env bash
# Issue 44's experiments: how much of a capture's quality its predicted buffers cost, and
# which training levers win it back. A scene (builtin:room unless SCENE says) rendered as
# three captures of the same photographs and true cameras (exact priors, --degrade network,
# --degrade monocular), each prior set scored against the exact one (bench/prior_accuracy),
# then Glint trained on each with the levers below and scored by `glint eval --breakdown` on
# the held-out views against the exact buffers (8-bit tonemapped PSNR of diffuse, specular,
# final).
#
# Usage: scripts/prior-experiments.sh [OUT]   (default out/prior-experiments)
# Environment: GLINT (build/glint), BENCH (build/bench), SCENE (builtin:room), ITERS (8000),
# RES (160x120), VIEWS (120, every 6th held out), SPP (32), TEST_SPP (64), EVAL_SPP (16),
# RUNS (which runs, default all: see `runs` below), TRUTH2 (1: also score against a second
# render of the held-out views, below).
set -euo pipefail

glint="${GLINT:-build/glint}"
bench="${BENCH:-build/bench}"
out="${1:-out/prior-experiments}"
iters="${ITERS:-8000}"
res="${RES:-160x120}"
views="${VIEWS:-120}"
here="$(cd "$(dirname "$0")" && pwd)"
[ -x "$glint" ] || { echo "prior-experiments: $glint not found (make build first)" >&2; exit 1; }
mkdir -p "$out/runs" "$out/configs"

# 1. The captures (the same photographs: same seed) and their priors' own accuracy. The
# net<buffer> captures have the network kind's errors on one kind of prior only
# (--degrade-only), to tell which prior's error costs what; they are made when a run needs them.
make_capture() {  # make_capture KIND
  local kind="$1" degrade=(--degrade "$1")
  case "$kind" in
    exact) degrade=(--degrade none) ;;
    network | monocular) ;;
    netradiance) degrade=(--degrade network --degrade-only diffuse,specular) ;;
    net*) degrade=(--degrade network --degrade-only "${kind#net}") ;;
  esac
  [ -f "$out/$kind/capture.json" ] || "$glint" synth "${SCENE:-builtin:room}" -o "$out/$kind" --layout capture --res "$res" \
    --train "$views" --holdout 6 --spp "${SPP:-32}" --test-spp "${TEST_SPP:-64}" "${degrade[@]}" --force
}
for kind in exact network monocular; do make_capture "$kind"; done
for kind in network monocular; do
  "$bench/prior_accuracy" "$out/$kind" "$out/exact" --holdout 6 --json "$out/priors_$kind.json"
done
# With TRUTH2=1, a second truth: the held-out views rendered again with another seed (the
# training views at 1 spp, unused). The priors are made from the exact capture's render and
# share its Monte Carlo noise, so their PSNR against it counts that noise as signal; against
# truth2 neither the priors nor a run shares it. Each run is then also scored against it
# (RUN/eval/metrics_truth2.json).
if [ "${TRUTH2:-0}" = 1 ]; then
  [ -f "$out/truth2/capture.json" ] || "$glint" synth "${SCENE:-builtin:room}" -o "$out/truth2" --layout capture \
    --res "$res" --train "$views" --holdout 6 --spp 1 --test-spp "${TEST_SPP:-64}" --seed 7 --degrade none --force
  for kind in exact network monocular; do
    "$bench/prior_accuracy" "$out/$kind" "$out/truth2" --holdout 6 --json "$out/priors_${kind}_truth2.json"
  done
fi

# 2. The levers, as config files (each a complete setting; none means Glint's defaults).
echo '{}' > "$out/configs/defaults.json"
cp "$here/real-capture-train.json" "$out/configs/preset.json"
echo '{"bounces": 2, "loss": {"depth": 0.0, "specular": 0.01}, "init": {"depth_residual_voxels": 0}}' \
  > "$out/configs/preset_fine_voxels.json"
echo '{"bounces": 2, "loss": {"depth": 0.0, "specular": 3.0}}' > "$out/configs/specular3.json"
echo '{"bounces": 2, "loss": {"depth": 0.0, "specular": 3.0, "f0_from_specular": 1.0}, "f0_tint_from_reflections": true}' \
  > "$out/configs/specular3_f0_tint.json"
# L_r's gradient into roughness and F0 (docs/derivations.md D15), alone and with the
# shift-invariant roughness term (which leaves the roughness level to it).
echo '{"loss": {"roughness_from_specular": 1.0}}' > "$out/configs/rfs.json"
echo '{"loss": {"roughness_from_specular": 0.1}}' > "$out/configs/rfs01.json"
echo '{"roughness_shift_invariant": true}' > "$out/configs/shift.json"
echo '{"roughness_shift_invariant": true, "loss": {"roughness_from_specular": 1.0}}' > "$out/configs/shift_rfs.json"
echo '{"loss": {"f0_from_specular": 1.0}}' > "$out/configs/ffs.json"
echo '{"f0_tint_from_reflections": true, "loss": {"f0_from_specular": 1.0}}' > "$out/configs/f0_tint.json"
# The network kind's best 8000-step setting (normal weight 2.5, depth band 0.1) with L_r's
# roughness gradient in place of the shift-invariant term.
echo '{"loss": {"normal": 2.5, "depth_band": 0.1, "roughness_from_specular": 1.0}}' > "$out/configs/n25_band_rfs.json"
echo '{"loss": {"roughness": 0.1}}' > "$out/configs/roughness01.json"
# The network kind's best setting (shift-invariant roughness, depth band 0.1) with the normal
# weight lowered further: its normals carry 4 degrees of noise, which L_r may shape better.
for w in 2.5 1 0.5; do
  echo "{\"roughness_shift_invariant\": true, \"loss\": {\"normal\": $w, \"depth_band\": 0.1}}" \
    > "$out/configs/n${w/./}_band_shift.json"
done
# The normals' learning rate decaying log-linearly to a tenth (nlr) or a hundredth (nlr100)
# over the run: with noisy normal priors Adam's constant-rate steps keep the normals
# jittering about their mean (docs/captures.md, "The normals' learning rate under noisy priors").
# (A second argument adds further "lr" fields.)
nlr() { echo "\"lr\": {\"normal_final\": $1, \"normal_decay_steps\": $iters${2:+, $2}}"; }
echo "{$(nlr 0.00025)}" > "$out/configs/nlr.json"
# The preset's own values (scripts/real-capture-train.json) with the decay added.
python3 -c 'import json, sys; c = json.load(open(sys.argv[1])); c["lr"] = json.loads("{" + sys.argv[2] + "}")["lr"]; print(json.dumps(c))' \
  "$out/configs/preset.json" "$(nlr 0.00025)" > "$out/configs/preset_nlr.json"
shift_band='"roughness_shift_invariant": true, "loss": {"normal": 2.5, "depth_band": 0.1}'
echo "{$shift_band, $(nlr 0.00025)}" > "$out/configs/n25_band_shift_nlr.json"
echo "{$shift_band, $(nlr 0.000025)}" > "$out/configs/n25_band_shift_nlr100.json"
# The roughness rate decaying the same way (the roughness priors are noisy too), on the best
# setting.
rlr100='"roughness_final": 0.000025, "roughness_decay_steps": '"$iters"
echo "{$shift_band, $(nlr 0.000025 "$rlr100")}" > "$out/configs/n25_band_shift_nlr100_rlr100.json"
# The depth band alone on Glint's defaults (the monocular kind's geometry at 8000 steps).
echo '{"loss": {"depth_band": 0.1}}' > "$out/configs/band.json"
echo "{\"loss\": {\"depth_band\": 0.1}, $(nlr 0.000025)}" > "$out/configs/band_nlr100.json"
# The same decay starting halfway (nlr100late): the normals follow the geometry freely while
# it still moves, then settle.
nlr_late="\"lr\": {\"normal_final\": 0.000025, \"normal_decay_start\": $((iters / 2)), \"normal_decay_steps\": $((iters / 2))}"
echo "{$shift_band, $nlr_late}" > "$out/configs/n25_band_shift_nlr100late.json"
echo '{"loss": {"normal": 2.5}}' > "$out/configs/normal25.json"
# The best setting with F0's tint learnt from the reflections (the monocular kind gives
# metalness only, so its tinted metals start grey): tried at 2000 steps on the monocular
# kind's geometry of the time, it had misplaced reflections to learn from.
echo "{\"roughness_shift_invariant\": true, \"f0_tint_from_reflections\": true, \"loss\": {\"normal\": 2.5, \"depth_band\": 0.1, \"f0_from_specular\": 1.0}, $(nlr 0.000025)}" \
  > "$out/configs/n25_band_shift_nlr100_f0_tint.json"
# The best setting with another seed: how far a run moves by chance alone.
echo "{\"seed\": 1, $shift_band, $(nlr 0.000025)}" > "$out/configs/n25_band_shift_nlr100_seed1.json"
# The paper's real-capture setting with the depth loss back, through the band: under COLMAP's
# cameras the best setting above lost to the preset (docs/captures.md), so the preset may be
# what to build on.
echo '{"bounces": 2, "loss": {"depth_band": 0.1, "specular": 0.01}}' > "$out/configs/preset_band.json"
# And with the depth only where 2 of each view's 8 neighbours agree within 2%
# (train/depth_consistency.h): issue 44's multi-view consistency lever.
echo '{"bounces": 2, "loss": {"depth_band": 0.1, "specular": 0.01, "depth_consistency": 0.02}}' \
  > "$out/configs/preset_band_consistent.json"
# The best setting with that check added.
echo "{\"roughness_shift_invariant\": true, \"loss\": {\"normal\": 2.5, \"depth_band\": 0.1, \"depth_consistency\": 0.02}, $(nlr 0.000025)}" \
  > "$out/configs/n25_band_shift_nlr100_consistent.json"
echo "{\"seed\": 1, \"roughness_shift_invariant\": true, \"loss\": {\"normal\": 2.5, \"depth_band\": 0.1, \"depth_consistency\": 0.02}, $(nlr 0.000025)}" \
  > "$out/configs/n25_band_shift_nlr100_consistent_seed1.json"
# The check at 1% instead of 2%: the network kind's depth is off by more than 5% on 2.5% of
# its pixels, and the 2% check keeps 98% of them.
echo "{\"roughness_shift_invariant\": true, \"loss\": {\"normal\": 2.5, \"depth_band\": 0.1, \"depth_consistency\": 0.01}, $(nlr 0.000025)}" \
  > "$out/configs/n25_band_shift_nlr100_consistent1.json"
# And with the dense initialisation leaving out the same untrusted depth
# (init.consistent_depth_only): the Gaussians a contradicted prior would place never made.
echo "{\"roughness_shift_invariant\": true, \"init\": {\"consistent_depth_only\": true}, \"loss\": {\"normal\": 2.5, \"depth_band\": 0.1, \"depth_consistency\": 0.02}, $(nlr 0.000025)}" \
  > "$out/configs/n25_band_shift_nlr100_consistent_init.json"
echo "{\"seed\": 1, \"roughness_shift_invariant\": true, \"init\": {\"consistent_depth_only\": true}, \"loss\": {\"normal\": 2.5, \"depth_band\": 0.1, \"depth_consistency\": 0.02}, $(nlr 0.000025)}" \
  > "$out/configs/n25_band_shift_nlr100_consistent_init_seed1.json"
# The best settings with a Huber normal term (loss.normal_huber, width 0.2, about 3.5 times the
# network kind's per-component noise): many views' noisy normal priors then meet near their
# mean rather than their median, which scatters less.
echo "{\"roughness_shift_invariant\": true, \"loss\": {\"normal\": 2.5, \"normal_huber\": 0.2, \"depth_band\": 0.1, \"depth_consistency\": 0.02}, $(nlr 0.000025)}" \
  > "$out/configs/n25_band_shift_nlr100_consistent_huber.json"
echo "{\"roughness_shift_invariant\": true, \"init\": {\"consistent_depth_only\": true}, \"loss\": {\"normal\": 2.5, \"normal_huber\": 0.2, \"depth_band\": 0.1, \"depth_consistency\": 0.02}, $(nlr 0.000025)}" \
  > "$out/configs/n25_band_shift_nlr100_consistent_init_huber.json"
# The monocular kind's best setting with F0's tint learnt from the reflections, on the second
# scene (builtin:spheres), whose tinted chrome spheres read grey through metalness.
# (k = 0, as measured before loss.f0_tint_prior's default became 0.1.)
echo "{\"roughness_shift_invariant\": true, \"f0_tint_from_reflections\": true, \"init\": {\"consistent_depth_only\": true}, \"loss\": {\"normal\": 2.5, \"depth_band\": 0.1, \"depth_consistency\": 0.02, \"f0_from_specular\": 1.0, \"f0_tint_prior\": 0}, $(nlr 0.000025)}" \
  > "$out/configs/n25_band_shift_nlr100_consistent_init_f0_tint.json"
# The same with a weak pull of the metals' F0 toward their grey prior (loss.f0_tint_prior):
# on builtin:room the tint drifted (its flat mirror went pink), the light it reflects being
# seen by the training views only in it, so F0's tint and that light's colour trade freely.
for pair in 01:0.1 03:0.3 10:1; do  # name:k (k = 1 is the plain F0 term, L_r's gate alone)
  kappa="${pair%%:*}"
  echo "{\"roughness_shift_invariant\": true, \"f0_tint_from_reflections\": true, \"init\": {\"consistent_depth_only\": true}, \"loss\": {\"normal\": 2.5, \"depth_band\": 0.1, \"depth_consistency\": 0.02, \"f0_from_specular\": 1.0, \"f0_tint_prior\": ${pair#*:}}, $(nlr 0.000025)}" \
    > "$out/configs/n25_band_shift_nlr100_consistent_init_f0_tint_prior$kappa.json"
done
sed 's/^{/{"seed": 1, /' "$out/configs/n25_band_shift_nlr100_consistent_init_f0_tint_prior01.json" \
  > "$out/configs/n25_band_shift_nlr100_consistent_init_f0_tint_prior01_seed1.json"
# ... and with L_r's F0 gradient at a tenth of its weight: does the room's loss scale with it?
sed 's/"f0_from_specular": 1.0/"f0_from_specular": 0.1/' "$out/configs/n25_band_shift_nlr100_consistent_init_f0_tint_prior01.json" \
  > "$out/configs/n25_band_shift_nlr100_consistent_init_f0_tint_prior01_ffs01.json"
# Since L_r's material gradient holds the compositing weights (docs/derivations.md D15), the
# k = 0.1 config names the runs made with it: the "_held" config is the same file (the runs
# of the name without it were made with the gradient moving the geometry).
cp "$out/configs/n25_band_shift_nlr100_consistent_init_f0_tint_prior01.json" \
  "$out/configs/n25_band_shift_nlr100_consistent_init_f0_tint_prior01_held.json"
# The network kind's best setting with the option (its F0 prior is an F0 image: since the
# option withholds L_r's F0 gradient there, this run is the run without it).
echo "{\"roughness_shift_invariant\": true, \"f0_tint_from_reflections\": true, \"loss\": {\"normal\": 2.5, \"normal_huber\": 0.2, \"depth_band\": 0.1, \"depth_consistency\": 0.02, \"f0_from_specular\": 1.0, \"f0_tint_prior\": 0.1}, $(nlr 0.000025)}" \
  > "$out/configs/n25_band_shift_nlr100_consistent_huber_f0_tint_prior01_held.json"
# The photograph term (loss.photograph): diffuse + specular fitted to the exact photographs
# beside the predicted priors, at weights 1 and 3.
for w in 1 3; do
  sed "s/\"f0_tint_prior\": 0.1}/\"f0_tint_prior\": 0.1, \"photograph\": $w}/" \
    "$out/configs/n25_band_shift_nlr100_consistent_init_f0_tint_prior01.json" \
    > "$out/configs/n25_band_shift_nlr100_consistent_init_f0_tint_prior01_photo$w.json"
done
# The preset with the camera-independent levers: the photograph term at 3 (and, where the F0
# prior is a metalness, the tint option), measured as candidates for the automatic preset.
echo '{"bounces": 2, "loss": {"depth": 0.0, "specular": 0.01, "photograph": 3.0}}' > "$out/configs/preset_photo3.json"
echo '{"bounces": 2, "f0_tint_from_reflections": true, "loss": {"depth": 0.0, "specular": 0.01, "f0_from_specular": 1.0, "f0_tint_prior": 0.1}}' \
  > "$out/configs/preset_tint.json"
sed 's/"f0_tint_prior": 0.1}/"f0_tint_prior": 0.1, "photograph": 3.0}/' "$out/configs/preset_tint.json" \
  > "$out/configs/preset_tint_photo3.json"
# Two oracles on the monocular capture, each with one prior taken from the exact capture: its
# F0 (monof0: the metals' tint given) and its depth (monoexactdepth): how much of the monocular
# kind's loss each of those priors' errors makes.
oracle_capture() {  # oracle_capture NAME PRIOR (the exact capture's PRIOR in the monocular one's place)
  [ -d "$out/$1" ] && return
  mkdir -p "$out/$1/priors"
  cp -al "$out/monocular/images" "$out/monocular/sparse" "$out/monocular/capture.json" "$out/$1/"
  for kind in diffuse specular normal roughness metalness depth; do
    [ "$kind" = "$2" ] || [ "$2.$kind" = "f0.metalness" ] || cp -al "$out/monocular/priors/$kind" "$out/$1/priors/"
  done
  cp -al "$out/exact/priors/$2" "$out/$1/priors/"
}
oracle_capture monof0 f0
oracle_capture monoexactdepth depth
# The monocular capture without its depth: initialised from the sparse points instead.
if [ ! -d "$out/monodepthless" ]; then
  mkdir -p "$out/monodepthless/priors"
  cp -al "$out/monocular/images" "$out/monocular/sparse" "$out/monocular/capture.json" "$out/monodepthless/"
  for kind in diffuse specular normal roughness metalness; do cp -al "$out/monocular/priors/$kind" "$out/monodepthless/priors/"; done
fi

train_and_eval() {  # train_and_eval RUN CAPTURE CONFIG
  local run="$out/runs/$1"
  if [ ! -f "$run/eval/metrics.json" ]; then
    make_capture "$2"
    "$glint" train "$out/$2" -o "$run" --holdout 6 --iters "$iters" --config "$out/configs/$3.json" --force
    "$glint" eval "$run" --dataset "$out/exact" --spp "${EVAL_SPP:-16}" --bounces 4 --breakdown
  fi
  if [ "${TRUTH2:-0}" = 1 ] && [ ! -f "$run/eval/metrics_truth2.json" ]; then
    "$glint" eval "$run" --dataset "$out/truth2" --spp "${EVAL_SPP:-16}" --bounces 4 -o "$run/eval/metrics_truth2.json"
  fi
}
runs="${RUNS:-exact_defaults exact_preset network_preset_fine_voxels network_preset network_defaults
  network_specular3 network_roughness01 network_normal25 monocular_preset_fine_voxels monocular_preset
  monocular_defaults monocular_specular3 monocular_specular3_f0_tint monodepthless_preset
  netnormal_defaults netroughness_defaults netradiance_defaults netdepth_defaults netf0_defaults
  network_rfs network_shift network_shift_rfs monocular_ffs monocular_f0_tint exact_rfs
  monocular_rfs network_rfs01 exact_rfs01 monocular_rfs01 network_f0_tint network_n25_band_rfs
  network_n25_band_shift network_n1_band_shift network_n05_band_shift
  network_n25_band_shift_nlr network_n25_band_shift_nlr100 monocular_nlr network_preset_nlr
  network_n25_band_shift_nlr100_rlr100 monocular_band monocular_band_nlr100
  monocular_n25_band_shift_nlr100 network_n25_band_shift_nlr100late monocular_n25_band_shift_nlr100late
  monocular_n25_band_shift_nlr100_f0_tint monocular_n25_band_shift_nlr100_seed1
  monocular_preset_band monocular_preset_band_consistent monocular_n25_band_shift_nlr100_consistent
  network_n25_band_shift_nlr100_consistent monocular_n25_band_shift_nlr100_consistent_init
  network_n25_band_shift_nlr100_consistent_init monocular_n25_band_shift_nlr100_consistent_init_seed1
  network_n25_band_shift_nlr100_consistent_seed1 network_n25_band_shift_nlr100_consistent1
  network_n25_band_shift_nlr100_consistent_huber monocular_n25_band_shift_nlr100_consistent_init_huber
  monocular_n25_band_shift_nlr100_consistent_init_f0_tint monof0_n25_band_shift_nlr100_consistent_init
  monoexactdepth_n25_band_shift_nlr100_consistent_init
  monocular_n25_band_shift_nlr100_consistent_init_f0_tint_prior01
  monocular_n25_band_shift_nlr100_consistent_init_f0_tint_prior03
  monocular_n25_band_shift_nlr100_consistent_init_f0_tint_prior01_seed1
  monocular_n25_band_shift_nlr100_consistent_init_f0_tint_prior10
  monocular_n25_band_shift_nlr100_consistent_init_f0_tint_prior01_ffs01
  monocular_n25_band_shift_nlr100_consistent_init_f0_tint_prior01_held
  network_n25_band_shift_nlr100_consistent_huber_f0_tint_prior01_held
  monocular_n25_band_shift_nlr100_consistent_init_f0_tint_prior01_photo1
  monocular_n25_band_shift_nlr100_consistent_init_f0_tint_prior01_photo3
  monocular_preset_tint_photo3 network_preset_photo3 monocular_preset_tint monocular_preset_photo3}"
for name in $runs; do
  capture="${name%%_*}"
  train_and_eval "$name" "$capture" "${name#*_}"
done

# 3. The table.
echo
printf "%-32s %8s %8s %8s %10s %8s\n" run diffuse specular final "depth RMSE" normal
for metrics in "$out"/runs/*/eval/metrics.json; do
  python3 - "$metrics" <<'EOF'
import json, os, sys
m = json.load(open(sys.argv[1]))["mean"]
f = lambda v: "-" if v is None else "%.2f" % v
run = os.path.basename(os.path.dirname(os.path.dirname(sys.argv[1])))
print("%-32s %8s %8s %8s %10s %8s" % (run, f(m["diffuse"]["psnr_tonemapped"]), f(m["specular"]["psnr_tonemapped"]),
      f(m["final"]["psnr_tonemapped"]), f(m.get("depth_rmse")), f(m.get("normal_angle_deg"))))
EOF
done
