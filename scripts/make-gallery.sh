#!/usr/bin/env bash
# Regenerates the pictures in doc/ with the cutaway binary (`make gallery`): models,
# cuts, variants, pieces, the default salad (OpenGL preview and POV-Ray render), the board
# plate and market scenes and the contact sheet of all templates. Seeded and deterministic: the same program
# gives the same pictures.
set -euo pipefail
cd "$(dirname "$0")/.."
cutaway=${CUTAWAY:-./build/cutaway}
run() { echo "+ cutaway $*" >&2; "$cutaway" -q --backend cpu "$@"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

run model templates/tomato.yaml --png doc/tomato-model.png --size 400
run section templates/tomato.yaml --plane y=26 --png doc/tomato-section.png --size 400
run variants templates/tomato.yaml --count 41 --seed 1 --sheet 41 --tile 80 -o "$tmp/variants"
cp "$tmp/variants/contact-sheet.png" doc/tomato-variants.png
run piece templates/tomato.yaml --cut wedges:6 --png doc/tomato-wedges.png
run piece templates/onion.yaml --cut halves --png doc/onion-halves.png
run piece templates/cucumber.yaml --cut slices:20 --png doc/cucumber-slices.png
# The scenes' exports (and their textures) go to the temporary folder.
run scene scenes/salad.yaml -o "$tmp/salad.pov" --png doc/salad.png --render doc/salad-povray.png
run scene scenes/board.yaml -o "$tmp/board.glb" --png doc/board.png
run scene scenes/plate.yaml -o "$tmp/plate.glb" --png doc/plate.png
run scene scenes/market.yaml -o "$tmp/market.glb" --png doc/market.png  # about 80 s
CUTAWAY="$cutaway" bash scripts/template-sheet.sh doc/templates-sheet.png
echo "gallery: wrote doc/*.png" >&2
