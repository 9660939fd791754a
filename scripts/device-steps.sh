#!/usr/bin/env bash
# Sourced by the device-check scripts: step NAME TIMEOUT_S COMMAND... runs a command, logs it to $out/NAME.log and records its status for the summary table.
#
# The caller sets $out (the log folder); the steps run so far are in the array `steps`, each
# as "NAME|STATUS|SECONDS". A failing step does not stop the others.

declare -a steps=()
step() {
  local name=$1 limit=$2
  shift 2
  local start
  start=$(date +%s%N)
  timeout "$limit" "$@" >"$out/$name.log" 2>&1
  local status=$?
  local seconds
  seconds=$(awk -v a="$start" -v b="$(date +%s%N)" 'BEGIN { printf "%.2f", (b - a) / 1e9 }')
  steps+=("$name|$status|$seconds")
  echo "== $name: exit $status in ${seconds} s"
  tail -n 25 "$out/$name.log"
}
