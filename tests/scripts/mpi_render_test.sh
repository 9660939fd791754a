#!/usr/bin/env bash
# CTest mpi_render: `glint synth`, `render` and `eval` under mpirun write exactly the files of
# one process (every image byte-identical, the same file lists, the same metrics apart from
# eval's "seconds"), with 2 ranks sharing whole views and 3 ranks sharing views in row bands
# (fewer views than ranks). Exits 77 (skipped) without mpirun or when glint was built
# without MPI. Usage: mpi_render_test.sh GLINT_BINARY WORK_FOLDER
set -euo pipefail
glint="$1"
work="$2"
"$(dirname "$0")/mpi_available.sh" "$glint" || exit $?
rm -rf "$work"
mkdir -p "$work"
cd "$work"
mpi() { local ranks="$1"; shift; mpirun --oversubscribe --allow-run-as-root -np "$ranks" "$glint" "$@" --threads 1; }
one() { "$glint" "$@" --threads 1; }

# The same files, byte for byte, in two folders.
same_tree() {
  if ! diff <(cd "$1" && find . -type f | sort) <(cd "$2" && find . -type f | sort); then
    echo "FAILED: $1 and $2 hold different files"
    exit 1
  fi
  local f
  for f in $(cd "$1" && find . -type f ! -name '*.json' | sort); do
    cmp "$1/$f" "$2/$f" || { echo "FAILED: $1/$f and $2/$f differ"; exit 1; }
  done
  # JSON files too, except eval's wall-clock time.
  for f in $(cd "$1" && find . -type f -name '*.json' | sort); do
    cmp <(grep -v '"seconds":' "$1/$f") <(grep -v '"seconds":' "$2/$f") ||
      { echo "FAILED: $1/$f and $2/$f differ"; exit 1; }
  done
  echo "same: $1 $2 ($(cd "$1" && find . -type f | wc -l) files)"
}

# Synthesis: 7 views over 2 ranks; 3 views over 3 ranks (the train split's one view on rank 0).
one synth builtin:spheres -o D1 --train 4 --test 3 --res 64x48 --spp 16
mpi 2 synth builtin:spheres -o D2 --train 4 --test 3 --res 64x48 --spp 16
same_tree D1 D2
one synth builtin:spheres -o S1 --train 1 --test 2 --res 64x48 --spp 4
mpi 3 synth builtin:spheres -o S3 --train 1 --test 2 --res 64x48 --spp 4
same_tree S1 S3

one train D1 -o R --iters 30 --batch-rays 2048

# Render: the test split's 3 views over 2 ranks; 2 views in bands over 3 ranks, progressive
# and denoised; one camera-path frame in bands over 2 ranks.
one render R -o V1
mpi 2 render R -o V2
same_tree V1 V2
one render R --dataset S1 -o W1 --res 96x72 --spp 4 --progressive --denoise
mpi 3 render R --dataset S1 -o W3 --res 96x72 --spp 4 --progressive --denoise
same_tree W1 W3
one render R -o F1 --path orbit --frames 1 --no-video
mpi 2 render R -o F2 --path orbit --frames 1 --no-video
same_tree F1 F2

# Eval: 3 views over 2 ranks; 2 views in bands over 3 ranks, with the breakdown and a region.
one eval R -o E1/metrics.json --save-images
mpi 2 eval R -o E2/metrics.json --save-images
same_tree E1 E2
one eval R --dataset S1 -o G1/metrics.json --save-images --spp 4 --breakdown --region=-1,-1,-1,1,1,1
mpi 3 eval R --dataset S1 -o G3/metrics.json --save-images --spp 4 --breakdown --region=-1,-1,-1,1,1,1
same_tree G1 G3
echo "PASSED: synth, render and eval under mpirun match one process"
