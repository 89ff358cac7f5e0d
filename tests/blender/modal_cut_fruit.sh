#!/usr/bin/env bash
# Runs tests/blender/modal_cut_fruit.py in a windowed Blender under xvfb-run; Blender's files
# (settings, the session it saves on quit) stay in OUT_DIR.
# Usage: tests/blender/modal_cut_fruit.sh ADDON.zip CUTAWAY SOURCE_DIR OUT_DIR
set -euo pipefail
addon=$1 cutaway=$2 source_dir=$3 out=$4
rm -rf "$out"
mkdir -p "$out/tmp" "$out/home"
export HOME="$out/home" TMPDIR="$out/tmp" BLENDER_USER_SCRIPTS="$out/user-scripts" \
       XDG_CONFIG_HOME="$out/home/config" XDG_CACHE_HOME="$out/home/cache"
timeout 240 xvfb-run -a blender --factory-startup --enable-event-simulate \
  --python "$source_dir/tests/blender/modal_cut_fruit.py" -- "$addon" "$cutaway" "$source_dir" \
  "$out" > "$out/blender.log" 2>&1 || true
if [[ ! -f "$out/modal.txt" ]]; then
  echo "Blender wrote no result; its log:" >&2
  tail -n 20 "$out/blender.log" >&2
  exit 1
fi
cat "$out/modal.txt"
[[ "$(cat "$out/modal.txt")" == passed ]]
