#!/usr/bin/env bash
# The independent-scene figures of the README: Glint at its defaults and the RGB-only
# baseline, trained on the validation scenes Blender Cycles renders (scripts/blender/), scored
# by `glint eval --spp 64` at its defaults (the run's render bounces: 4) and with the 2
# bounces training traces, with the error breakdown, the
# mirror-only object's pixels where the scene has one, the training time and the ground
# truth's own noise level (two seeds of its test views, noise.json).
#
# Usage: scripts/validation-experiments.sh [VAL_ROOT] [RUNS]
#   VAL_ROOT (default out/validation) holds one dataset per scene; missing ones are rendered
#   with scripts/blender/make-validation-scenes.sh (needs Blender). RUNS defaults to
#   VAL_ROOT/runs. Finished runs and evaluations are kept, so the script resumes.
# Environment: GLINT (build/glint), SCENES ("spheres_room mirror_room"), EVAL_SPP (64),
# ITERS (training steps; empty: glint train's default), CONFIG (a --config file for the
# Glint runs, to measure one lever at a time; its runs are named after the file).
set -euo pipefail

glint="${GLINT:-build/glint}"
val="${1:-out/validation}"
runs="${2:-$val/runs}"
scenes="${SCENES:-spheres_room mirror_room}"
eval_spp="${EVAL_SPP:-64}"
iters=()
[ -n "${ITERS:-}" ] && iters=(--iters "$ITERS")
config=()
variant=glint
if [ -n "${CONFIG:-}" ]; then
  config=(--config "$CONFIG")
  variant="glint_$(basename "$CONFIG" .json)"
fi
here="$(cd "$(dirname "$0")" && pwd)"

[ -x "$glint" ] || { echo "validation-experiments: $glint not found (make build first)" >&2; exit 1; }
for scene in $scenes; do
  if [ ! -f "$val/$scene/transforms_test.json" ]; then
    SCENES="$scene" "$here/blender/make-validation-scenes.sh" "$val"
  fi
done
mkdir -p "$runs"

# The mirror-only object's box as --region's X0,Y0,Z0,X1,Y1,Z1, or nothing.
region_of() {
  [ -f "$1/validation.json" ] || return 0
  python3 -c 'import json,sys; b=json.load(open(sys.argv[1]))["mirror_only_object"]; print(",".join("%g" % v for v in b["min"] + b["max"]))' \
    "$1/validation.json"
}

for scene in $scenes; do
  data="$val/$scene"
  glint_run="$runs/${scene}_$variant"
  rgb_run="$runs/${scene}_rgb"
  [ -f "$glint_run/scene.ply" ] || "$glint" train "$data" -o "$glint_run" "${iters[@]}" "${config[@]}" --force
  [ -f "$rgb_run/scene.ply" ] || "$glint" train "$data" -o "$rgb_run" --baseline rgb "${iters[@]}" --force
  region="$(region_of "$data")"
  region_flag=()
  [ -n "$region" ] && region_flag=("--region=$region")
  [ -f "$glint_run/eval/metrics.json" ] ||
    "$glint" eval "$glint_run" --spp "$eval_spp" --breakdown "${region_flag[@]}" --save-images
  [ -f "$glint_run/eval/metrics_2_bounces.json" ] ||
    "$glint" eval "$glint_run" --spp "$eval_spp" --bounces 2 "${region_flag[@]}" -o "$glint_run/eval/metrics_2_bounces.json"
  [ -f "$rgb_run/eval/metrics.json" ] || "$glint" eval "$rgb_run" --spp "$eval_spp" "${region_flag[@]}"
done

# The table: 8-bit filmic PSNR (dB) on the test views; the mirror-only object's final over
# its pixels; training time; the ground truth's seed-to-seed PSNR (a render against the
# infinite-sample truth is about 3 dB above it).
echo
python3 - "$runs" "$val" "$variant" $scenes <<'EOF'
import csv, json, os, sys
runs, val, variant, scenes = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]

def load(path):
    return json.load(open(path)) if os.path.exists(path) else None

def db(x):
    return "-" if x is None else "%.2f" % x

def train_time(run):
    rows = list(csv.DictReader(open(os.path.join(run, "log.csv"))))
    s = float(rows[-1]["wall_s"])
    return "%d:%02d" % (s // 60, s % 60)

print("%-14s %-22s %9s %9s %9s %12s %8s" % ("scene", "run", "diffuse", "specular", "final", "mirror-only", "train"))
for scene in scenes:
    # metrics.json is at `glint eval`'s defaults; runs evaluated before render_bounces
    # (2026-11-26) also have metrics_4_bounces.json, runs after it metrics_2_bounces.json.
    candidates = ("metrics.json", "metrics_2_bounces.json", "metrics_4_bounces.json")
    for name, metrics in [(variant, f) for f in candidates] + [("rgb", "metrics.json")]:
        run = os.path.join(runs, "%s_%s" % (scene, name))
        m = load(os.path.join(run, "eval", metrics))
        if m is None:
            continue
        mean = m["mean"]
        region = m.get("region", {}).get("pooled", {}).get("final_psnr_tonemapped")
        label = "%s, %d bounces" % (name, m["bounces"])
        # The baseline bakes reflections into its colours: only its final image compares.
        split = name != "rgb"
        print("%-14s %-22s %9s %9s %9s %12s %8s" % (scene, label,
              db(mean["diffuse"]["psnr_tonemapped"] if split else None),
              db(mean["specular"]["psnr_tonemapped"] if split else None), db(mean["final"]["psnr_tonemapped"]),
              db(region), train_time(run)))
    noise = load(os.path.join(val, scene, "noise.json"))
    if noise:
        p = noise["psnr_8bit_filmic_seed_vs_seed_db"]
        print("%-14s %-22s %9s %9s %9s" % (scene, "truth seed vs seed", db(p.get("diffuse")), db(p.get("specular")),
                                            db(p.get("render"))))
EOF
