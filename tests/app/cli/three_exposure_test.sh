#!/usr/bin/env bash
# Each shipped scene rendered by three.js as doc/lighting.md tells its users to (linear tone
# mapping at the exposure in the scene's extras, a hemisphere light of its ambient_lux): the
# mean luma of the objects' pixels (Rec. 709 weights on 8-bit sRGB values) must lie in
# LOW..HIGH, neither dark nor blown out. The frames stay in DIR/three-*.png to be looked at.
# Usage: tests/app/cli/three_exposure_test.sh SOURCE_DIR DIR LOW HIGH
set -euo pipefail
source_dir=$1 dir=$2 low=$3 high=$4
status=0
for glb in "$dir"/*.glb; do
  name=$(basename "$glb" .glb)
  report=$(node "$source_dir/tests/tools/load_gltf_three.mjs" "$glb" \
                --screenshot "$dir/three-$name.png" 400 300 | tail -n 1)
  echo "$name: $report"
  node -e '
    const [report, low, high] = [JSON.parse(process.argv[1]), +process.argv[2], +process.argv[3]];
    const y = report.object_luminance;
    if (!report.ok) { console.error(`not loaded: ${report.error}`); process.exit(1); }
    if (!(report.object_fraction > 0.05)) { console.error("the objects fill under 5 % of the frame"); process.exit(1); }
    if (!(y >= low && y <= high)) { console.error(`object luma ${y.toFixed(1)} outside ${low}..${high}`); process.exit(1); }
    console.log(`object luma ${y.toFixed(1)} in ${low}..${high}`);
  ' "$report" "$low" "$high" || status=1
done
exit $status
