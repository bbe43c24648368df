#!/usr/bin/env bash
# kinray set-up on Debian 12: installs the Debian packages that are missing, builds into build/,
# then either renders the default scene or runs the whole test suite.
#
#   bash tools/setup.sh render   # install, build, render wavy-sphere to out/wavy-sphere/ (default)
#   bash tools/setup.sh test     # install, build, run every test (ctest)
#   bash tools/setup.sh build    # install and build only
#   bash tools/setup.sh sanitize # install, build into build-sanitize/ with ASan + UBSan, run every test
#   bash tools/setup.sh fuzz     # install clang too, build the libFuzzer harnesses into build-fuzz/,
#                                # run each for KINRAY_FUZZ_SECONDS (default 30) from its corpus
set -euo pipefail

mode="${1:-render}"
case "$mode" in
  render | test | build | sanitize | fuzz) ;;
  *)
    echo "usage: bash tools/setup.sh [render|test|build|sanitize|fuzz]" >&2
    exit 2
    ;;
esac

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

packages=(
  cmake ninja-build g++ pkg-config ccache
  libeigen3-dev libtbb-dev libembree-dev libassimp-dev assimp-testmodels libosmesa6-dev
  libopencv-imgcodecs-dev libopencv-imgproc-dev libopencv-videoio-dev
  libcli11-dev nlohmann-json3-dev libgtest-dev libbenchmark-dev libgmp-dev
)
# libFuzzer comes with clang's runtime; only the fuzz mode needs them.
if [[ "$mode" == fuzz ]]; then packages+=(clang-14 libclang-rt-14-dev); fi

# dpkg-query answers in milliseconds, so a machine that has everything never touches apt.
missing=()
for package in "${packages[@]}"; do
  status="$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null || true)"
  [[ "$status" == "install ok installed" ]] || missing+=("$package")
done
if ((${#missing[@]} > 0)); then
  echo "setup: installing ${missing[*]}"
  sudo=()
  if [[ "$(id -u)" != 0 ]]; then
    command -v sudo >/dev/null || { echo "setup: need root or sudo to install packages" >&2; exit 1; }
    sudo=(sudo)
  fi
  "${sudo[@]}" apt-get update
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
fi

# ccache keeps compiled objects across builds and clones on one machine (a second clone, the
# sanitizer build after a change, CI on a developer's machine): paths are hashed relative to the
# checkout, so every clone shares the cache.
export CCACHE_BASEDIR="$root"
export KINRAY_CMAKE_ARGS="${KINRAY_CMAKE_ARGS:--DCMAKE_CXX_COMPILER_LAUNCHER=ccache}"

# The sanitizer and fuzz builds live in folders of their own (tools/checks.sh).
if [[ "$mode" == sanitize || "$mode" == fuzz ]]; then
  exec bash tools/checks.sh "$mode"
fi

echo "setup: building into build/"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER=ccache
# Rendering needs only the program; the tests need everything (the suite runs the program too).
if [[ "$mode" == test ]]; then
  cmake --build build -j "$(nproc)"
else
  cmake --build build -j "$(nproc)" --target kinray
fi

case "$mode" in
  render)
    # Slow motion, what the kinetic grid is for: 32 frames per keyframe interval over half a
    # second; --backend auto (the default) measures the shot and says which backend it took.
    build/bin/kinray render wavy-sphere --time 0:0.5 --inbetweens 32 --out out/wavy-sphere
    echo "setup: the 385 frames are in $root/out/wavy-sphere/ (frame_00000.png .. frame_00384.png)"
    ;;
  test)
    ctest --test-dir build --output-on-failure -j2
    ;;
  build)
    echo "setup: the program is $root/build/bin/kinray"
    ;;
esac
