#!/usr/bin/env bash
# Godot 3 (Debian's godot3) imports cutaway's files written for it (`--for godot`, a batch's
# `export: {for: godot}`) as a game needs them: a `piece` file of tomato wedges, a batch asset
# of kiwi halves and a small scene (`scene --for godot`: its settled pieces loose, no backdrop)
# go into a new project, the editor runs headless under xvfb-run until it has imported all
# three (it does not quit by itself: stopped once every import is written), then a
# script loads each imported scene (inspect.gd) and check_import.py checks the bodies.
# Everything Godot writes stays in DIR (its settings and caches too).
# Usage: tests/godot/import_test.sh CUTAWAY SOURCE_DIR DIR
set -euo pipefail
cutaway=$1 source_dir=$(cd "$2" && pwd) dir=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$dir"
mkdir -p "$dir/project" "$dir/home"
export HOME="$dir/home" XDG_CONFIG_HOME="$dir/home/config" XDG_DATA_HOME="$dir/home/data" \
       XDG_CACHE_HOME="$dir/home/cache"
project="$dir/project"
printf 'config_version=4\n\n[application]\n\nconfig/name="cutaway import test"\n' \
  > "$project/project.godot"
cp "$here/inspect.gd" "$project/"

"$cutaway" -q piece "$source_dir/templates/tomato.yaml" --cut wedges:6 --for godot \
  -o "$project/tomato.glb"
printf 'format: cutaway-batch/1\nname: godot\nitems:\n  - {template: %s, count: 1, cuts: [{type: halves}]}\nexport: {for: godot}\n' \
  "$source_dir/templates/kiwi.yaml" > "$dir/batch.yaml"
"$cutaway" -q batch "$dir/batch.yaml" -o "$dir/batch" --no-cache
cp "$dir/batch/kiwi-0-halves.glb" "$project/kiwi.glb"
placed=$("$cutaway" --stats -q scene "$source_dir/tests/data/scenes/small.yaml" --no-cache \
           --for godot -o "$project/scene.glb" 2>&1 >/dev/null |
         python3 -c 'import json, sys; print(json.loads(sys.stdin.read().splitlines()[-1])["placed"])')

# The editor imports on its first scan; each import ends with its .md5 file.
setsid xvfb-run -a godot3 --path "$project" -e > "$dir/editor.log" 2>&1 &
editor=$!
for _ in $(seq 1 120); do
  (($(ls "$project/.import/"*.md5 2>/dev/null | wc -l) >= 3)) && break
  sleep 1
done
kill -- -"$editor" 2>/dev/null || true
wait "$editor" 2>/dev/null || true
if (($(ls "$project/.import/"*.md5 2>/dev/null | wc -l) < 3)); then
  echo "Godot did not import the three files in 120 s:" >&2
  tail -n 20 "$dir/editor.log" >&2
  exit 1
fi

status=0
for case in tomato:6 kiwi:2 "scene:$placed"; do
  name=${case%%:*} pieces=${case##*:}
  result=$(CUTAWAY_SCENE="res://$name.glb" timeout 120 xvfb-run -a godot3 --path "$project" \
             -s inspect.gd 2> "$dir/inspect-$name.log" | grep '^CUTAWAY_RESULT' || true)
  echo "$name.glb:"
  if [[ -z "$result" ]]; then
    echo "error: Godot printed no result for $name.glb" >&2
    tail -n 20 "$dir/inspect-$name.log" >&2
    status=1
    continue
  fi
  python3 "$here/check_import.py" "$result" "$pieces" || status=1
done
exit $status
