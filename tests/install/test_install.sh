#!/usr/bin/env bash
# Tests of cmake/Install.cmake, cmake/gpmConfig.cmake.in and models/data_dir.cpp
# (issue 18.4): `cmake --install BUILD --prefix P` into a folder under the build
# tree; the files are there; a consumer project (tests/install/consumer) is
# configured with find_package(gpm CONFIG REQUIRED), built, installed into P
# and run from outside the source tree, where it must load the installed robot
# file through gpm::models_dir() and calibrate; the installed gpm finds the
# installed data (also after the prefix is moved), simulates an installed
# scenario; the installed Python module imports. Everything is removed on exit.
#   test_install.sh BUILD_DIR SOURCE_DIR WORK_PARENT
set -u
BUILD=$1 SRC=$2 PARENT=$3
source "$SRC/tests/cli/cli_lib.sh"   # check, expect_out, expect_err, finish; $tmp (unused)
mkdir -p "$PARENT"
work=$(mktemp -d "$PARENT/install_test.XXXXXX")
trap 'rm -rf "$tmp" "$work"' EXIT
unset GPM_DATA_DIR
P=$work/prefix
expect() {  # name, condition (shell test)
  if eval "$2"; then passed=$((passed+1)); else echo "FAIL $1: $2"; fail=$((fail+1)); fi
}

check "install" 0 cmake --install "$BUILD" --prefix "$P"
for f in bin/gpm bin/gpm-drive-emulator lib/libgpm_models.a lib/libgpm_calib.a lib/libgpm_sim.a \
         include/gpm/models/robot_yaml.hpp include/gpm/calib/lm.hpp include/gpm/hw/plugin/gpm_backend_plugin.h include/gpm/calib/excitation/excitation.hpp \
         lib/cmake/gpm/gpmConfig.cmake lib/cmake/gpm/gpmConfigVersion.cmake lib/cmake/gpm/gpmTargets.cmake \
         share/gpm/models/gpm2002.yaml share/gpm/scenarios/main.yaml share/gpm/hw/examples/twin.yaml; do
  expect "installed $f" "[[ -s '$P/$f' ]]"
done
expect "no source path in the package" "! grep -rq '$SRC' '$P/lib/cmake/gpm'"
# Tell the installed robot file apart from the source tree's (which the
# binaries could otherwise fall back to).
sed -i 's/^name: .*/name: GPM2002-installed/' "$P/share/gpm/models/gpm2002.yaml"

# The consumer project, against the installed package only.
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
if grep -q '^GPM_NATIVE:BOOL=ON' "$BUILD/CMakeCache.txt"; then
  # A native build's package refuses consumers (cmake/gpmConfig.cmake.in).
  check "native package refused" 1 cmake -S "$SRC/tests/install/consumer" -B "$work/consumer" -G Ninja \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$P" "${launcher[@]}"
  expect_err "refusal names GPM_NATIVE" "GPM_NATIVE"
  cd "$work"
else
  check "consumer configure" 0 cmake -S "$SRC/tests/install/consumer" -B "$work/consumer" -G Ninja \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$P" "${launcher[@]}"
  expect_out "consumer sees gpm_DATA_DIR" "gpm_DATA_DIR $P/share/gpm$"
  check "consumer build" 0 cmake --build "$work/consumer"
  check "consumer install" 0 cmake --install "$work/consumer" --prefix "$P"
  cd "$work"   # outside the source and build trees' data
  check "consumer runs" 0 "$P/bin/gpm_consumer"
  expect_out "consumer data folder" "^models_dir $P/share/gpm/models$"
  expect_out "consumer loads the installed robot" "^robot GPM2002-installed$"
  expect_out "consumer calibrates" "^calibration: converged 1"
  # Built elsewhere, the consumer is pointed at the data by the package's gpm_DATA_DIR.
  check "consumer with GPM_DATA_DIR" 0 env GPM_DATA_DIR="$P/share/gpm" "$work/consumer/gpm_consumer"
  expect_out "GPM_DATA_DIR robot" "^robot GPM2002-installed$"
fi

# The installed gpm: kin with the installed robot, a scenario of the installed library.
check "installed gpm kin" 0 "$P/bin/gpm" kin home
expect_out "installed robot file" "^robot +GPM2002-installed$"
expect_out "home" "x = 216\.500000 mm, y = 250\.000000 mm"
check "installed gpm kin json" 0 "$P/bin/gpm" kin ik 230 260 --json
expect_out "json robot" '"robot": "GPM2002-installed"'
check "installed scenario" 0 "$P/bin/gpm" simulate "$P/share/gpm/scenarios/simulate_circle.yaml" -o "$work/sim"
expect "scenario samples" "[[ \$(wc -l <'$work/sim/samples.csv') -gt 1 ]]"
check "drive emulator" 0 "$P/bin/gpm-drive-emulator" --help
# gpm help prints the installed documents (an installed user has no source tree).
check "installed gpm help schema" 0 "$P/bin/gpm" help schema
expect "help schema is the installed SCHEMA" "'$P/bin/gpm' help schema | cmp -s - '$P/share/gpm/scenarios/SCHEMA.md'"
check "installed gpm help formats" 0 "$P/bin/gpm" help formats
# The install moves as a whole.
mv "$P" "$work/moved"
check "moved gpm kin" 0 "$work/moved/bin/gpm" kin home
expect_out "moved robot file" "^robot +GPM2002-installed$"
P=$work/moved

# The Python module, when built.
shopt -s nullglob
mods=("$P"/lib/python3/dist-packages/gpm*.so)
if (( ${#mods[@]} )); then
  check "python import" 0 env PYTHONPATH="$P/lib/python3/dist-packages" /usr/bin/python3 -c \
    'import gpm; print(gpm.models_dir()); print(gpm.load_robot().name)'
  expect_out "python data folder" "^$P/share/gpm/models$"
  expect_out "python robot" "^GPM2002-installed$"
fi

finish
