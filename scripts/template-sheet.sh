#!/usr/bin/env bash
# The contact sheet of the template library (doc/templates.md): all thirteen templates of the
# paper's Table 1, each cut the way that shows its inside best, pieces laid out cut face up
# (the volcano standing, its cut faces toward the camera), labelled, in one PNG.
#
#   scripts/template-sheet.sh [OUT.png]        (default doc/templates-sheet.png)
#
# Uses ./build/cutaway (or $CUTAWAY) with the cpu backend; deterministic, about 10 s on 2 cores.
# Each argument of `cutaway sheet` is TEMPLATE[:CUT][@VIEW]: CUT as `cutaway piece --cut`, or
# `across` (one horizontal cut at mid-height; halves when left out); VIEW up (default) or upright.
set -euo pipefail
cd "$(dirname "$0")/.."
cutaway=${CUTAWAY:-./build/cutaway}
out=${1:-doc/templates-sheet.png}
t=templates
set -x
"$cutaway" -q --backend cpu sheet --tile 360 -o "$out" \
  $t/tomato.yaml:across $t/onion.yaml $t/persimmon.yaml:across $t/pepper.yaml:across \
  $t/avocado.yaml $t/apple.yaml:across $t/okra.yaml:slices:20 $t/star_fruit.yaml:slices:15 \
  $t/strawberry.yaml $t/cucumber.yaml:slices:15 $t/kiwi.yaml:across $t/volcano.yaml@upright \
  $t/kidney.yaml
