#!/usr/bin/env bash
# The contact sheet of the template library (doc/templates.md): every shipped template twice,
# whole and cut the way that shows its inside best, pieces laid out cut face up (the volcano
# standing, its cut faces toward the camera), labelled, in one PNG. Each template is its seeded
# variant 1, so grains (seeds, pips, arils) show.
#
#   scripts/template-sheet.sh [OUT.png]        (default doc/templates-sheet.png)
#
# Uses ./build/cutaway (or $CUTAWAY) with the cpu backend; deterministic, a few minutes on 2
# cores. Each argument of `cutaway sheet` is TEMPLATE[:CUT][@VIEW]: CUT as `cutaway piece
# --cut`, or `across` (one horizontal cut at mid-height); VIEW up (default) or upright.
set -euo pipefail
cd "$(dirname "$0")/.."
cutaway=${CUTAWAY:-./build/cutaway}
out=${1:-doc/templates-sheet.png}
# template:cut, in the sheet's order: the paper's Table 1, then fruit, vegetables and dishes
cuts=(
  tomato:across onion:halves persimmon:across pepper:across avocado:halves apple:across
  okra:slices:20 star_fruit:slices:15 strawberry:halves cucumber:slices:15 kiwi:across
  volcano:halves@upright kidney:halves
  orange:across lemon:across lime:across grapefruit:across watermelon:halves
  cantaloupe:across honeydew:across banana:halves pear:halves peach:halves plum:halves
  apricot:halves cherry:halves grape:halves mango:halves pomegranate:across
  dragon_fruit:halves passion_fruit:halves fig:halves papaya:across coconut:halves
  carrot:halves radish:across beetroot:across potato:halves eggplant:halves
  zucchini:across mushroom:halves garlic:across leek:across
  boiled_egg:halves maki_roll:across layered_cake:wedges:6
)
args=()
for c in "${cuts[@]}"; do
  name=${c%%:*}
  args+=("templates/$name.yaml:whole@upright" "templates/$name.yaml:${c#*:}")
done
set -x
"$cutaway" -q --backend cpu sheet --seed 1 --tile 260 --columns 10 -o "$out" "${args[@]}"
