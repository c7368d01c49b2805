#!/usr/bin/env bash
# A design for axis ranges with and without the robot's dictionary (issue 39's question: does
# the dictionary pay for range designs?). Builds the robot-level pick-and-place dictionary
# (about 4 minutes on two cores, 35 MB) into OUT_DIR unless it is there, then times
# `solve --ranges` on the pick-and-place motion's own box with --setup alone and with
# --dict (benches/dictionary_speedup.sh: whole-process wall times, the ratio, same path).
#
# Usage: bash benches/range_dictionary.sh [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-target/range_dictionary}"
mkdir -p "$out"
cargo build --release --quiet
setup=robots/viper_s850/pick_and_place.toml
dict="$out/viper_s850_robot_level.cdict"
if [ ! -f "$dict" ]; then
  target/release/cable-dict -q build "$setup" -o "$dict"
fi
bash benches/dictionary_speedup.sh "$out" "$setup" "$dict" --ranges=motions/viper_s850/pick_and_place_box.toml
