#!/usr/bin/env bash
# On a lent GPU machine: runs the GPU tests (also under compute-sanitizer) and the GPU benchmarks of a build carried in device-carry/, then prints one table.
#
# Usage (from the repository root on the GPU machine):  scripts/device-check.sh [QUICK=0]
# Build and pack first on a Debian machine: `make build` then `scripts/pack-device-build.sh`,
# and carry device-carry/ (docs/gpu.md). Logs and JSON go to $OUT (the device tool's
# folder that comes back) or /tmp/glint-device-out. About 6 minutes on an H100.
set -uo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo"
out=${OUT:-/tmp/glint-device-out}
mkdir -p "$out"
quick=${1:-0}

# shellcheck source=scripts/device-unpack.sh
source scripts/device-unpack.sh /tmp/glint-device || exit 1
bin=$GLINT_DEVICE_DIR/build
work=/tmp/glint-device-work
rm -rf "$work" && mkdir -p "$work"

# shellcheck source=scripts/device-steps.sh
source scripts/device-steps.sh

nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.sm,clocks.max.sm --format=csv >"$out/gpu.txt" 2>&1
cat "$out/gpu.txt"
"$bin/glint" --version | tee "$out/version.txt"
cores=$(nproc)

# 1. The GPU against the CPU, then the same tests under compute-sanitizer's memcheck.
step gpu_tests 150 "$bin/tests/test_cuda" --gtest_filter='-GpuTraining.*'  # training: device-train-check.sh
if command -v compute-sanitizer >/dev/null; then
  step gpu_memcheck 150 compute-sanitizer --tool memcheck --error-exitcode 9 --leak-check full \
    "$bin/tests/test_cuda" --gtest_filter='GpuTracer.*:GpuRenderer.*'
fi

# 2. The tracer alone: the GPU against the fast CPU tracer, same rays, on 2 and on all cores.
step tracer_2_threads 120 "$bin/bench/tracer_bench" --tracers fast cuda cuda-warp --threads 2 --gaussians 500000 \
  --res-width 1024 --res-height 768 --repeats 2 --json "$out/tracer_2.json"
[ "$quick" = 1 ] || step tracer_all_threads 90 "$bin/bench/tracer_bench" --tracers fast cuda cuda-warp --threads "$cores" \
  --gaussians 500000 --res-width 1024 --res-height 768 --repeats 3 --json "$out/tracer_all.json"

# 3. Rendering through renderGaussianView on both devices; writes the scene and cameras.
step render_compare 120 "$bin/bench/gpu_bench" --gaussians 500000 --width 1024 --height 768 --bounces 4 \
  --compare-spp 2 --gpu-spp 64 --threads "$cores" --write "$work" --views 20 --json "$out/gpu_bench.json"

# 4. The product: `glint render` of 20 views at 1024x768, 64 spp, 4 bounces, on the GPU,
#    loading and writing included.
step glint_render 100 "$bin/glint" render "$work/scene.ply" --dataset "$work/dataset" --split test \
  --res 1024x768 --spp 64 --bounces 4 --device cuda -o "$work/render"

# 5. The viewer over HTTP as the page drives it, at 1024x768 with 2 bounces.
step viewer 90 "$bin/bench/viewer_bench" "$work/scene.ply" --dataset "$work/dataset" --device cuda \
  --width 1024 --height 768 --bounces 2 --threads "$cores" --seconds 4 --cameras 3 --json "$out/viewer.json"

# 6. An edit's relighting (issue 43's batches) on each device: the chrome sphere of the scene
#    moved 0.5 m, glint edit with healing and relighting, the GPU's against all CPU cores.
cat >"$work/move.json" <<'JSON'
{"glint_edits": 1, "selections": {"it": {"sphere": {"center": [-1.3, 0.6, 0.0], "radius": 0.65}}},
 "operations": [{"op": "translate", "selection": "it", "offset": [0, 0, 0.5]}]}
JSON
step relight_gpu 120 "$bin/glint" edit "$work/scene.ply" "$work/move.json" -o "$work/edited_gpu.ply" --device cuda
[ "$quick" = 1 ] || step relight_cpu 150 "$bin/glint" edit "$work/scene.ply" "$work/move.json" \
  -o "$work/edited_cpu.ply" --device cpu --threads "$cores"

# The table.
python3 - "$out" "${steps[@]}" <<'EOF'
import json, os, sys
out = sys.argv[1]
rows = [s.split("|") for s in sys.argv[2:]]
def load(name):
    try:
        return json.load(open(os.path.join(out, name)))
    except Exception:
        return None
print("\n== device-check summary ==")
print(open(os.path.join(out, "gpu.txt")).read().strip())
print(f"{'step':22} {'exit':>5} {'seconds':>9}")
for name, status, seconds in rows:
    print(f"{name:22} {status:>5} {float(seconds):9.1f}")
for label, name in (("2 threads", "tracer_2.json"), ("all threads", "tracer_all.json")):
    t = load(name)
    if not t:
        continue
    for row in t:
        print(f"tracer {label:11} {row['tracer']:6} {row['scene']:14} {row['mrays_per_s']:9.2f} Mrays/s  "
              f"{row['speedup_vs_baseline']:8.1f}x vs fast  build {row['build_s']:.3f} s")
g = load("gpu_bench.json")
if g:
    print(f"render view {g['width']}x{g['height']} {g['bounces']} bounces: CPU ({g['cpu_threads']} threads) "
          f"{g['cpu_view_s']:.3f} s, GPU {g['gpu_view_s']:.3f} s for {g['compare_spp']} spp = {g['speedup']:.1f}x; "
          f"mean |diff| {g['mean_abs_difference']:.3g}, largest {g['largest_abs_difference']:.3g}; "
          f"GPU {g['gpu_spp']} spp {g['gpu_many_spp_s']:.3f} s ({g['gpu_mpaths_per_s']:.1f} M paths/s)")
v = load("viewer.json")
if v:
    cams = ", ".join(f"{c['camera']}: {c['samples_per_s']:.1f}" for c in v["still"])
    print(f"viewer {v['width']}x{v['height']} {v['bounces']} bounces ({v['tracer']}): "
          f"{v['still_samples_per_s']:.1f} samples/s ({cams}); moving {v['moving_fps']:.1f} fps")
for name in ("relight_gpu", "relight_cpu"):
    try:
        lines = [l.strip() for l in open(os.path.join(out, name + ".log")) if ": relit " in l]
    except OSError:
        continue
    if lines:
        print(f"{name}: {lines[-1]}")
EOF
