#!/usr/bin/env bash
# Fixture of the viewer tests: the shipped salad, plate and market scenes as .glb, made with the
# default options into DIR, each cut afresh (--no-cache) (the three.js exposure test and the Blender add-on tests read them).
# Usage: tests/app/cli/shipped_scenes.sh CUTAWAY SOURCE_DIR DIR
set -euo pipefail
cutaway=$1 source_dir=$2 dir=$3
rm -rf "$dir"
mkdir -p "$dir"
for scene in salad plate market; do
  "$cutaway" scene "$source_dir/scenes/$scene.yaml" -o "$dir/$scene.glb" -q --no-cache
done
ls -l "$dir"
