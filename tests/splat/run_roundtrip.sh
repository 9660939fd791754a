#!/usr/bin/env bash
# Round trip of Glint's compressed exports through PlayCanvas's splat-transform (CTest:
# splat_transform_roundtrip): Glint writes a small scene as .spz and .compressed.ply (plain
# and with baked SH of degree 3), splat-transform converts each to a plain .ply, and
# splat_roundtrip_check compares those with what Glint wrote, then reads them as a user's
# 3DGS file (degree 0 and 3) and checks the colours Glint shows. Exits 77 (skipped) when Node
# or npm is missing; installs splat-transform from the lockfile (npm ci) when node_modules
# is absent. Usage: run_roundtrip.sh GLINT_BINARY CHECK_BINARY WORK_FOLDER
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
glint="$1" check="$2" work="$3"
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "SKIPPED: node and npm are needed for the splat-transform round trip"
  exit 77
fi
if [ ! -x "$here/node_modules/.bin/splat-transform" ]; then
  (cd "$here" && npm ci --no-audit --no-fund --loglevel=error)
fi
splat_transform="$here/node_modules/.bin/splat-transform"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export GLINT_QUIET=1

"$check" make scene.ply
# The reference of the baked exports: the same bake in the 3DGS layout (the bake is seeded,
# so all three formats get the same coefficients).
bake=(--bake-reflections --sh-degree 3 --bake-directions 16)
"$glint" export scene.ply --format 3dgs "${bake[@]}" -o baked.ply
status=0
for variant in plain baked; do
  flags=()
  reference=scene.ply
  if [ "$variant" = baked ]; then flags=("${bake[@]}"); reference=baked.ply; fi
  "$glint" export scene.ply --format spz "${flags[@]}" -o "$variant.spz"
  "$glint" export scene.ply --format compressed-ply "${flags[@]}" -o "$variant.compressed.ply"
  for format in spz compressed-ply; do
    input="$variant.spz"
    [ "$format" = compressed-ply ] && input="$variant.compressed.ply"
    "$splat_transform" -q -w "$input" "$variant-$format-decoded.ply"
    "$check" compare "$reference" "$variant-$format-decoded.ply" "$format" || status=1
    "$check" import "$variant-$format-decoded.ply" || status=1
  done
done
exit $status
