#!/usr/bin/env bash
# BodyGen/BodyView setup: installs every Debian package the project needs (idempotent),
# configures and builds. Subcommands:
#   ./setup.sh            install dependencies, build Release into build/
#   ./setup.sh deps       install host dependencies only
#   ./setup.sh cross-deps install the arm64 multiarch libraries + cross toolchain + qemu
#   ./setup.sh demo       build, then build the sample anatomy and open the kiosk (see README)
#   ./setup.sh test       build and run the whole test suite (what CI runs)
set -euo pipefail
cd "$(dirname "$0")"
ROOT=$PWD
JOBS=${JOBS:-$(nproc)}

HOST_PACKAGES=(
  build-essential cmake ninja-build pkg-config file git ca-certificates
  clang libclang-rt-14-dev clang-format
  libglfw3-dev libegl-dev libgles-dev libgbm-dev libdrm-dev libglm-dev libevdev-dev
  libtinyobjloader-dev nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev
  libmeshoptimizer-dev libstb-dev fonts-dejavu-core zlib1g-dev
  libnifti2-dev libdcmtk-dev libpolyclipping-dev libtinygltf-dev libassimp-dev libsystemd-dev libseat-dev libudev-dev systemd
  libegl-mesa0 libgl1-mesa-dri libgles2 xvfb xauth
  glmark2-data python3 python3-pydicom mricron-data dpkg-dev
  assimp-utils python3-vtk9 python3-numpy nodejs libdraco-dev
  libharfbuzz-dev libfribidi-dev libicu-dev fonts-noto-core fonts-noto-cjk
)
CROSS_PACKAGES=(
  g++-aarch64-linux-gnu qemu-user
  libc6:arm64 libstdc++6:arm64
  libglfw3-dev:arm64 libegl-dev:arm64 libgles-dev:arm64 libgbm-dev:arm64 libdrm-dev:arm64
  libevdev-dev:arm64 libtinyobjloader-dev:arm64 libgtest-dev:arm64 libgmock-dev:arm64
  libmeshoptimizer-dev:arm64 libstb-dev:arm64 zlib1g-dev:arm64 libpolyclipping-dev:arm64
  libegl-mesa0:arm64 libgl1-mesa-dri:arm64 libgles2:arm64 libsystemd-dev:arm64 libseat-dev:arm64 libudev-dev:arm64
  libharfbuzz-dev:arm64 libfribidi-dev:arm64 libicu-dev:arm64
)

missing_packages() {
  local p
  for p in "$@"; do
    dpkg-query -W -f='${db:Status-Status}\n' "$p" 2>/dev/null | grep -qx installed || echo "$p"
  done
}

as_root() {
  if [ "$(id -u)" = 0 ]; then "$@"; else
    echo "setup.sh: need root to run: sudo $*" >&2
    exit 1
  fi
}

install_packages() {
  local missing
  missing=$(missing_packages "$@")
  [ -z "$missing" ] && return 0
  echo "setup.sh: installing:" $missing
  if [ "$(id -u)" != 0 ]; then
    echo "setup.sh: missing packages; run: sudo apt-get update && sudo apt-get install -y" $missing >&2
    exit 1
  fi
  if [ -z "${BODY_APT_UPDATED:-}" ]; then apt-get update -qq; export BODY_APT_UPDATED=1; fi
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $missing >/dev/null
}

# The Khronos glTF-Validator (npm, not in Debian) for the export tests, into the
# git-ignored tools/node/; without npm the tests that need it skip and say so.
node_tools() {
  if command -v npm >/dev/null && [ ! -f "$ROOT/tools/node/node_modules/gltf-validator/package.json" ]; then
    npm install --prefix "$ROOT/tools/node" --no-audit --no-fund --silent gltf-validator >/dev/null ||
      echo "setup: npm could not install gltf-validator; the glTF validation tests will skip" >&2
  fi
}

deps() { install_packages "${HOST_PACKAGES[@]}"; node_tools; }

cross_deps() {
  if ! dpkg --print-foreign-architectures | grep -qx arm64; then
    as_root dpkg --add-architecture arm64
    unset BODY_APT_UPDATED
  fi
  install_packages "${CROSS_PACKAGES[@]}"
}

configure_build() { # dir build-type [extra cmake args...]
  local dir=$1 type=$2; shift 2
  cmake -S "$ROOT" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE="$type" "$@" >/dev/null
  cmake --build "$dir" -j "$JOBS"
}

build() { configure_build build Release; }

case "${1:-build}" in
  deps) deps ;;
  cross-deps) cross_deps ;;
  build) deps; build ;;
  demo) deps; build; exec "$ROOT/scripts/demo.sh" ;;
  test) deps; cross_deps; exec "$ROOT/scripts/test.sh" ;;
  *) echo "usage: ./setup.sh [build|deps|cross-deps|demo|test]" >&2; exit 2 ;;
esac
