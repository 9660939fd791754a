#!/bin/sh
# Chooses `glint train --batch-rays` by wall-clock time to quality: trains the same dataset
# with several batch sizes, each stopped (Ctrl-C, which saves) after a time budget, and
# prints, per batch size, the test diffuse PSNR reached at fixed wall times and the time
# at which it first reached 32 and 33 dB (logged with --eval-spp 4). Usage:
#   scripts/batch_study.sh DATASET OUT_FOLDER SECONDS [BATCH...]   (default batches 4096 16384 65536)
set -eu
[ $# -ge 3 ] || { echo "usage: $0 DATASET OUT_FOLDER SECONDS [BATCH...]" >&2; exit 2; }
dataset=$1; out=$2; budget=$3; shift 3
batches=${*:-4096 16384 65536}
glint=${GLINT:-build/glint}
mkdir -p "$out"
for b in $batches; do
  # Score the test views about every 15 s of training whatever the batch size.
  every=$(( 4000000 / b )); [ "$every" -ge 1 ] || every=1
  if [ ! -f "$out/b$b/log.csv" ]; then
    timeout -s INT "$budget" "$glint" train "$dataset" -o "$out/b$b" --batch-rays "$b" --iters 1000000 \
      --eval-every "$every" --save-every 1000000 >"$out/b$b.out" 2>&1 || true
  fi
done
printf '%-8s %8s %8s %10s %10s %10s %10s %10s\n' batch steps wall_s "PSNR@60s" "PSNR@180s" "PSNR@end" "t(32dB)" "t(33dB)"
for b in $batches; do
  awk -F, -v b="$b" 'NR > 1 {
      steps = $1; wall = $12
      if ($13 != "") { p = $13
        if (wall <= 60) p60 = p; if (wall <= 180) p180 = p; last = p
        if (p >= 32 && t32 == "") t32 = wall; if (p >= 33 && t33 == "") t33 = wall }
    } END { printf "%-8s %8d %8.0f %10s %10s %10s %10s %10s\n", b, steps, wall, p60, p180, last,
            (t32 == "" ? "-" : t32), (t33 == "" ? "-" : t33) }' "$out/b$b/log.csv"
done
