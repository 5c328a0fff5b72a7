#!/usr/bin/env bash
# Installs the Debian 12 packages mrslam needs (only those missing), then configures and builds
# it with CMake (Release, -j2). Re-running it with nothing changed takes a few seconds.
#   scripts/setup.sh            install + build everything
#   MRSLAM_BUILD_DIR=dir        build folder (default: build/ in the project)
#   MRSLAM_JOBS=n               parallel build jobs (default: 2)
#   MRSLAM_SETUP_TESTS=1        also what the tests need (Chromium, for the live viewer's test)
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${MRSLAM_BUILD_DIR:-$root/build}"
jobs="${MRSLAM_JOBS:-2}"

packages=(
  cmake make g++ git
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools
  libeigen3-dev libnanoflann-dev libceres-dev
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev
  libopencv-features2d-dev libopencv-calib3d-dev
  liboctomap-dev libyaml-cpp-dev libspdlog-dev libcli11-dev nlohmann-json3-dev zlib1g-dev
  libcpp-httplib-dev
  libgtest-dev libgmock-dev libbenchmark-dev
)
# The tests also drive the live viewer in a headless browser.
if [ "${MRSLAM_SETUP_TESTS:-0}" = 1 ]; then
  packages+=(chromium)
fi

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

# fastddsgen runs on Java: any Java will do; Debian's when there is none.
if ! command -v java >/dev/null 2>&1; then
  missing+=(default-jre-headless)
fi

if [ ${#missing[@]} -gt 0 ]; then
  echo "mrslam setup: installing ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then
    sudo_cmd=(sudo)
  fi
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q \
    --no-install-recommends "${missing[@]}"
fi

if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build_dir" -j "$jobs"
