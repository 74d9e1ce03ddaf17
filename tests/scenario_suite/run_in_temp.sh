#!/usr/bin/env bash
# Runs `gpm run SCENARIO -o DIR --quiet` with DIR a fresh temporary folder that
# is removed afterwards: for scenarios that sample through the hardware
# interface, whose samples.csv is never overwritten, so that the suite can run
# again in the same build. Exit status: gpm's.
set -u
GPM="$1"; SCENARIO="$2"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$GPM" run "$SCENARIO" -o "$tmp/run" --quiet
