#!/usr/bin/env bash
# Fixture of the viewer tests: one shipped scene (salad, plate or market) as DIR/SCENE.glb, made
# with the default options and cut afresh (--no-cache); the three.js exposure test and the
# Blender add-on tests read them. One CTest test per scene, so that they run side by side.
# Usage: tests/app/cli/shipped_scenes.sh CUTAWAY SOURCE_DIR DIR SCENE
set -euo pipefail
cutaway=$1 source_dir=$2 dir=$3 scene=$4
mkdir -p "$dir"
rm -f "$dir/$scene.glb"
"$cutaway" scene "$source_dir/scenes/$scene.yaml" -o "$dir/$scene.glb" -q --no-cache
ls -l "$dir/$scene.glb"
