#!/usr/bin/env bash
# Packs the GPU-check executables of a build plus the shared libraries they need into OUT_DIR, to carry to a lent GPU machine (docs/gpu.md).
#
# Usage: scripts/pack-device-build.sh [BUILD_DIR=build] [OUT_DIR=device-carry]
# Run on the build machine after `make build`. Writes OUT_DIR/bin.tar.gz (executables under
# their repository-relative paths, e.g. build/glint), OUT_DIR/libs.tar.gz (lib/<soname>, flat, so
# LD_LIBRARY_PATH=<dir>/lib finds them) and OUT_DIR/manifest.txt. scripts/device-unpack.sh undoes it.
set -euo pipefail

# The lent machine takes at most 64 MiB of carried paths in all; keep a margin for the rest.
LIMIT_BYTES=$((60 * 1024 * 1024))

die() { echo "pack-device-build: $*" >&2; exit 1; }

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo"

build_arg=${1:-build}
out_arg=${2:-device-carry}
[ $# -le 2 ] || die "too many arguments (usage: scripts/pack-device-build.sh [BUILD_DIR] [OUT_DIR])"

[ -d "$build_arg" ] || die "build folder '$build_arg' does not exist: run 'make build' first"
# The tarball stores paths relative to the repository root, so the build folder must lie inside it.
build_rel=$(realpath --relative-to="$repo" "$build_arg")
case "$build_rel" in
  ..*|/*) die "build folder '$build_arg' is outside the repository $repo: the carried paths are repository-relative" ;;
esac
[ -x "$build_rel/glint" ] || die "'$build_rel/glint' is missing or not executable: run 'make build' first"

for tool in ldd tar gzip readelf; do
  command -v "$tool" >/dev/null || die "'$tool' is not installed"
done

# Only git-ignored paths can be carried beside the checkout; refuse to write somewhere that
# would show up as untracked files (or be carried twice).
out_rel=$(realpath -m --relative-to="$repo" "$out_arg")
case "$out_rel" in
  ..*|/*) die "output folder '$out_arg' is outside the repository $repo: only paths inside it can be carried" ;;
  .) die "output folder '$out_arg' is the repository root: name a folder inside it" ;;
esac
git -C "$repo" check-ignore -q "$out_rel/" \
  || die "output folder '$out_rel' is not git-ignored: add it to .gitignore (/device-carry/ is) or pick another"
mkdir -p "$out_rel"
out="$repo/$out_rel"

# GLINT_NATIVE (on by default) compiles for this machine's CPU; the GPU machine's CPU may lack
# some of those instructions, and the executables would then die of SIGILL there.
native=$(sed -n 's/^GLINT_NATIVE:BOOL=//p' "$build_rel/CMakeCache.txt" 2>/dev/null || true)
march=$(gcc -march=native -Q --help=target 2>/dev/null | awk '$1 == "-march=" { print $2; exit }' || true)
case "$native" in
  ON|on|1|TRUE|true|YES|yes)
    echo "pack-device-build: warning: '$build_rel' was configured with GLINT_NATIVE=ON (-march=native, here ${march:-unknown});" \
         "if the GPU machine's CPU lacks some of its instructions the executables stop with 'Illegal instruction'." \
         "Configure with -DGLINT_NATIVE=OFF for a portable build." >&2
    native_note="GLINT_NATIVE=ON, -march=native = ${march:-unknown}" ;;
  *) native_note="GLINT_NATIVE=${native:-unknown}" ;;
esac

# --- The executables ----------------------------------------------------------------------
bins=("$build_rel/glint")
# Test executables meant for the GPU (none may exist yet). CMakeFiles holds objects, not tests.
if [ -d "$build_rel/tests" ]; then
  while IFS= read -r f; do bins+=("$f"); done < <(
    find "$build_rel/tests" -path '*/CMakeFiles' -prune -o -type f -perm -u+x \
      \( -name '*cuda*' -o -name '*gpu*' \) -print | sort)
fi
for f in "$build_rel"/bench/*_bench; do
  [ -f "$f" ] && [ -x "$f" ] && bins+=("$f")
done

# --- The libraries they need --------------------------------------------------------------
# The GPU machine's own glibc and GCC runtime are newer than Debian 12's and backward
# compatible, and carrying them would clash with its loader; the CUDA driver libraries must
# come from the driver installed there, matched to its kernel module.
system_lib() {
  case "$1" in
    linux-vdso.so*|ld-linux*|libc.so*|libm.so*|libmvec.so*|libpthread.so*|libdl.so*|librt.so*) return 0 ;;
    libresolv.so*|libutil.so*|libanl.so*|libnsl.so*|libnss_*|libBrokenLocale.so*|libthread_db.so*) return 0 ;;
    libstdc++.so*|libgcc_s.so*) return 0 ;;
    libcuda.so*|libnvidia-*|libnvcuvid.so*) return 0 ;;
  esac
  return 1
}

stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/lib"

declare -A carried=()   # soname -> resolved real file
missing=()
for bin in "${bins[@]}"; do
  # ldd lists the whole closure (the libraries' own dependencies too), keyed by the name the
  # loader searches for, which is the file name LD_LIBRARY_PATH must offer.
  while read -r name arrow path _; do
    [ "$arrow" = "=>" ] || continue
    system_lib "$name" && continue
    if [ "$path" = "not" ]; then missing+=("$name (needed by $bin)"); continue; fi
    carried[$name]=$(readlink -f "$path")
  done < <(ldd "$bin")
done
[ ${#missing[@]} -eq 0 ] || die "ldd cannot resolve these here, so they cannot be carried: ${missing[*]}"

# oneTBB dlopens its scalable allocator from libtbb's own folder and quietly falls back to
# malloc without it; carry it so the GPU machine times the same allocator as this one.
# OpenMPI's dlopen'd components (openmpi/lib/openmpi3/mca_*) are not carried: glint only calls
# MPI_Init under mpirun (src/core/cluster.cpp), and the GPU check runs it as one process.
if [ -n "${carried[libtbb.so.12]:-}" ]; then
  tbbmalloc=$(dirname "${carried[libtbb.so.12]}")/libtbbmalloc.so.2
  [ -e "$tbbmalloc" ] && carried[libtbbmalloc.so.2]=$(readlink -f "$tbbmalloc")
fi

for name in "${!carried[@]}"; do
  src=${carried[$name]}
  soname=$(readelf -d "$src" | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p')
  [ -z "$soname" ] || [ "$soname" = "$name" ] \
    || echo "pack-device-build: warning: $src is needed as $name but its SONAME is $soname" >&2
  cp "$src" "$stage/lib/$name"
done

# Check the staged set is complete: with only it on the library path, everything but the
# excluded system family must resolve into it (here the system folders still answer, so a
# library missing from the set would show as resolving to /usr/lib or /lib).
for bin in "${bins[@]}"; do
  while read -r name arrow path _; do
    [ "$arrow" = "=>" ] || continue
    system_lib "$name" && continue
    case "$path" in
      "$stage/lib/"*) ;;
      *) die "$bin: $name resolves to '$path', not to the staged lib/ folder" ;;
    esac
  done < <(env -i LD_LIBRARY_PATH="$stage/lib" ldd "$bin")
done

# --- The tarballs ------------------------------------------------------------------------
rm -f "$out/bin.tar.gz" "$out/libs.tar.gz" "$out/manifest.txt"
tar -C "$repo" -cf - "${bins[@]}" | gzip -9 > "$out/bin.tar.gz"
tar -C "$stage" -cf - lib | gzip -9 > "$out/libs.tar.gz"

# What was packed, and from which commit: the executables only match a checkout of that commit.
{
  echo "commit: $(git -C "$repo" rev-parse HEAD 2>/dev/null || echo unknown)$(git -C "$repo" diff --quiet HEAD 2>/dev/null || echo ' (with uncommitted changes)')"
  echo "packed: $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(. /etc/os-release && echo "$PRETTY_NAME")"
  echo "cpu: $native_note"
  echo "executables:"
  printf '  %s\n' "${bins[@]}"
  echo "libraries:"
  (cd "$stage/lib" && for f in *; do printf '  %-32s %10d bytes\n' "$f" "$(stat -c %s "$f")"; done)
} > "$out/manifest.txt"

size() { stat -c %s "$1"; }
mib() { awk -v b="$1" 'BEGIN { printf "%.1f MiB", b / 1048576 }'; }
bin_bytes=$(size "$out/bin.tar.gz")
lib_bytes=$(size "$out/libs.tar.gz")
total=$((bin_bytes + lib_bytes + $(size "$out/manifest.txt")))
echo "pack-device-build: ${#bins[@]} executables, ${#carried[@]} libraries"
printf '  %-14s %s (%d bytes)\n' bin.tar.gz "$(mib "$bin_bytes")" "$bin_bytes"
printf '  %-14s %s (%d bytes)\n' libs.tar.gz "$(mib "$lib_bytes")" "$lib_bytes"
printf '  %-14s %s (%d bytes)\n' total "$(mib "$total")" "$total"
if [ "$total" -gt "$LIMIT_BYTES" ]; then
  die "the packed files in $out_arg total $(mib "$total"), over the $(mib "$LIMIT_BYTES") limit (the lent machine takes 64 MiB of carried paths): leave out executables or libraries"
fi
echo "pack-device-build: carry '$out_rel' and run scripts/device-unpack.sh on the GPU machine"
