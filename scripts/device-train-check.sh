#!/usr/bin/env bash
# On a lent GPU machine: checks and times training on the GPU (issue 42) with a build carried in device-carry/, then prints one table.
#
# Usage (from the repository root on the GPU machine):  scripts/device-train-check.sh
# Build and pack first on a Debian machine: `make build` then `scripts/pack-device-build.sh`,
# and carry device-carry/ (docs/gpu.md). Logs and JSON go to $OUT (the device tool's folder
# that comes back) or /tmp/glint-device-out. About 8 minutes on an H100 by estimate (not yet
# run on one); scripts/device-check.sh checks the tracer and rendering.
set -uo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo"
out=${OUT:-/tmp/glint-device-out}
mkdir -p "$out"

# shellcheck source=scripts/device-unpack.sh
source scripts/device-unpack.sh /tmp/glint-device || exit 1
bin=$GLINT_DEVICE_DIR/build
work=/tmp/glint-device-train
rm -rf "$work" && mkdir -p "$work"

# shellcheck source=scripts/device-steps.sh
source scripts/device-steps.sh

nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv >"$out/gpu.txt" 2>&1
cat "$out/gpu.txt"
"$bin/glint" --version | tee "$out/version.txt"
cores=$(nproc)

# 1. One batch's gradients on the GPU against the CPU (both ways of summing), reproducible
#    sums, 500 steps on each device scored alike; then the first two under memcheck.
step train_tests 240 "$bin/tests/test_cuda" --gtest_filter='GpuTraining.*'
if command -v compute-sanitizer >/dev/null; then
  step train_memcheck 180 compute-sanitizer --tool memcheck --error-exitcode 9 --leak-check full \
    "$bin/tests/test_cuda" --gtest_filter='GpuTraining.OneBatch*:GpuTraining.SortedSums*'
fi

# 2. A step's parts on each device, the same scene and batches (train_bench's own dataset,
#    builtin:spheres at 160x120; 300 warm-up steps, reflections from step 100).
#    On the GPU also with wavefronts of 65,536 paths instead of 8,192 (fewer round trips).
for run in "cuda 8192" "cuda 65536" "fast 8192"; do
  set -- $run
  step "train_bench_$1_$2" 200 "$bin/bench/train_bench" --tracer "$1" --wavefront-rays "$2" --threads "$cores" \
    --warmup 300 --reflection-warmup 100 --batches 8 --json "$out/train_bench_$1_$2.json"
done

# 3. The product: `make demo`'s training (builtin:spheres, 100 views at 160x120, 8000 steps,
#    defaults) on the GPU, its dataset made first (not timed).
step synth 150 "$bin/glint" synth builtin:spheres -o "$work/spheres" --res 160x120 --train 100 --test 20 --spp 64 \
  --test-spp 64 --threads "$cores"
step demo_train_gpu 240 "$bin/glint" train "$work/spheres" -o "$work/run_gpu" --device cuda --threads "$cores" \
  --eval-views 0

# 4. The paper's scale of a step (issue 42): 884,736 rays (one 1152x768 view's worth) a step
#    from the same dataset, wavefronts of 65,536 paths; last, so that running out of time
#    loses nothing else.
step train_bench_cuda_paper 200 "$bin/bench/train_bench" --tracer cuda --wavefront-rays 65536 --threads "$cores" \
  --batch-rays 884736 --warmup 60 --reflection-warmup 30 --batches 2 --json "$out/train_bench_cuda_paper.json"

python3 - "$out" "${steps[@]}" <<'EOF'
import json, os, sys
out = sys.argv[1]
rows = [s.split("|") for s in sys.argv[2:]]
print("\n== device-train-check summary ==")
print(open(os.path.join(out, "gpu.txt")).read().strip())
print(f"{'step':22} {'exit':>5} {'seconds':>9}")
for name, status, seconds in rows:
    print(f"{name:22} {status:>5} {float(seconds):9.1f}")
for run in ("cuda_8192", "cuda_65536", "fast_8192", "cuda_paper"):
    try:
        t = json.load(open(os.path.join(out, f"train_bench_{run}.json")))
    except Exception:
        continue
    p = t.get("step_parts_ms", {})
    print(f"train_bench {run:10}: " + ", ".join(f"{k} {v:.1f} ms" for k, v in p.items()))
    for name, row in t.get("passes", {}).items():
        print(f"  {name:55} {row['mrays_per_s']:9.3f} Mrays/s")
try:
    lines = [l.strip() for l in open(os.path.join(out, "demo_train_gpu.log")) if "steps/s" in l or "done" in l]
    print("demo training on the GPU:", lines[-2:] if lines else "no progress line")
except OSError:
    pass
EOF
