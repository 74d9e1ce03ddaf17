#!/usr/bin/env bash
# Installs every build and test dependency of the toolkit from Debian 12 packages.
# Idempotent: packages already present are left alone; safe to run on every build.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config ninja-build
  libeigen3-dev libceres-dev libyaml-cpp-dev libboost-dev nlohmann-json3-dev
  libmujoco-dev libqhull-dev libmujoco-samples
  libosmesa6-dev libavcodec-dev libavformat-dev libswscale-dev libavutil-dev libpng-dev ffmpeg
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev libfmt-dev libspdlog-dev
  universal-ctags  # scripts/check_code_shape.sh (test repo.code_shape)
  libmodbus-dev
  libpagmo-dev
  python3-scipy python3-numpy
  python3-dev pybind11-dev python3-pybind11 python3-pytest
  python3-distributed python3-dask python3-pandas python3-matplotlib  # gpm.study on Dask (python/README.md)
  chromium  # headless browser: the report tests (tests/report/test_html_in_browser.cpp, test_report_screenshots.sh), scripts/readme_pictures.sh
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  SUDO=""
  [[ $(id -u) -eq 0 ]] || SUDO="sudo"
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
