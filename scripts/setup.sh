#!/usr/bin/env bash
# Sets up aavio on a fresh Debian 12 machine: installs every Debian package the project uses
# (non-interactive, idempotent; runs `apt-get update` only when something is missing) and builds
# into ./build. Safe to run again: a second run installs nothing and rebuilds incrementally.
#
#   scripts/setup.sh              install dependencies and build (Release)
#   scripts/setup.sh --deps-only  only install dependencies
#   scripts/setup.sh --ros        also Debian's ROS1 (roscpp, tf2, rosbag, rospy): builds
#                                 aavio_ros_node and runs its end-to-end test (docs/ros.md)
#   BUILD_DIR=... BUILD_TYPE=Debug CMAKE_ARGS="-DAAVIO_SANITIZE=ON" scripts/setup.sh
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$repo/build}
build_type=${BUILD_TYPE:-Release}
deps_only=false
ros=false
for arg in "$@"; do
  case "$arg" in
    --deps-only) deps_only=true ;;
    --ros) ros=true ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) echo "setup.sh: unknown argument '$arg' (try --help)" >&2; exit 2 ;;
  esac
done

# Build tools (clang and its sanitizer and libFuzzer runtimes for scripts/sanitize.sh and
# scripts/fuzz.sh), libraries (docs/architecture.md), the Python module's pybind11 and pytest, and the
# independent fixture writers the tests run with /usr/bin/python3 (docs/io.md).
packages=(
  build-essential cmake pkgconf git clang-format clang libclang-rt-dev
  libeigen3-dev libopencv-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libtbb-dev
  libhdf5-dev hdf5-filter-plugin-blosc-serial hdf5-tools liblz4-dev libzstd-dev libbz2-dev libsqlite3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3-dev pybind11-dev python3-pytest
  python3 python3-yaml python3-numpy python3-h5py python3-hdf5plugin python3-matplotlib
  python3-rosbag python3-genpy python3-genmsg
)
# ROS1 as Debian packages it (Noetic-era 1.15/1.16): the node's libraries, roscore, rosbag,
# and rospy with the message modules the end-to-end test's listener imports.
if $ros; then
  packages+=(
    libroscpp-dev libtopic-tools-dev libtf2-ros-dev libsensor-msgs-dev libnav-msgs-dev
    ros-core librosbag-dev python3-rosbag python3-rospy python3-nav-msgs python3-geometry-msgs
    python3-std-msgs iproute2
  )
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup.sh: installing ${#missing[@]} Debian package(s): ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup.sh: need root or sudo to install packages" >&2; exit 1; }
    sudo=sudo
  fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -q
  # --no-install-recommends keeps libopencv-dev from pulling in ~1 GB of optional packages.
  $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
else
  echo "setup.sh: all ${#packages[@]} Debian packages already installed"
fi

$deps_only && exit 0

jobs=$(nproc 2>/dev/null || echo 2)
cmake_args=(-S "$repo" -B "$build_dir" -DCMAKE_BUILD_TYPE="$build_type")
# CI (CI=true) treats warnings as errors.
if [ "${CI:-}" = "true" ]; then cmake_args+=(-DAAVIO_WERROR=ON); fi
# shellcheck disable=SC2206
[ -n "${CMAKE_ARGS:-}" ] && cmake_args+=(${CMAKE_ARGS})
cmake "${cmake_args[@]}"
cmake --build "$build_dir" -j "$jobs"
echo "setup.sh: built $build_dir/bin/aavio"
