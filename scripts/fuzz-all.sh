#!/usr/bin/env bash
# Runs every cargo-fuzz target for RUNS executions (default 10⁶) from its seed corpus and
# prints one line per target: executions, seconds, and whether it found a crash.
#   bash scripts/fuzz-all.sh [RUNS] [TARGET …]   (default: every target)
# Built without a sanitizer (-s none: the parsers are safe Rust; 2–3 times the speed).
# Needs the nightly toolchain and cargo-fuzz (`cargo install cargo-fuzz`). Seeds: the bundled
# robots, setups, cables, motions (first 3 kB) and dictionaries, copied by this script.
set -uo pipefail
cd "$(dirname "$0")/../fuzz"
runs="${1:-1000000}"
seed() { mkdir -p "corpus/$1"; shift_target="$1"; shift; for f in "$@"; do cp "$f" "corpus/$shift_target/"; done; }
seed parse_urdf ../robots/viper_s850/viper_s850.urdf ../tests/data/urdf_real/my_robot_description/urdf/robot.urdf
seed parse_setup ../robots/viper_s850/*.toml ../tests/data/*.toml
seed parse_cable ../cables/*.toml
seed parse_waypoints ../motions/viper_s850/*.toml
mkdir -p corpus/parse_motion
for f in ../motions/viper_s850/*.csv; do head -c 3000 "$f" > "corpus/parse_motion/$(basename "$f")"; done
seed read_resealed ../dictionaries/*.cdict
seed read_mesh ../tests/data/tetrahedron.stl ../tests/data/robots/franka_description/meshes/collision/link4.stl
seed parse_trusted_keys seeds/trusted_keys
seed check_signatures seeds/check_signatures.sig
cargo +nightly fuzz build -O -s none >/dev/null 2>&1 || { echo "fuzz build failed" >&2; exit 2; }
status=0
targets=("${@:2}")
[ ${#targets[@]} -gt 0 ] || targets=(parse_urdf parse_cable parse_setup parse_motion parse_waypoints read_dictionary read_resealed dictionary_structured read_mesh parse_trusted_keys check_signatures)
for target in "${targets[@]}"; do
  log="artifacts/$target.log"
  mkdir -p artifacts
  start=$(date +%s)
  cargo +nightly fuzz run -O -s none "$target" "corpus/$target" -- -runs="$runs" -max_len=65536 \
      -rss_limit_mb=4096 -timeout=30 -print_final_stats=1 > "$log" 2>&1
  rc=$?
  done_runs=$(grep -aoE "Done [0-9]+ runs" "$log" | grep -oE "[0-9]+" | tail -1)
  echo "$target: ${done_runs:-?} executions in $(( $(date +%s) - start )) s, $( [ $rc -eq 0 ] && echo 'no crash' || echo "CRASH (see $log)")"
  [ $rc -eq 0 ] || status=1
done
exit $status
