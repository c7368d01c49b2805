#!/usr/bin/env bash
# One solve of a cell against a solve per motion, in one run: the whole-process wall time of
# each single solve and of the cell solve, their lengths, the ratios (cell / slowest single,
# cell / sum of singles), and `check` of the cell's mounting against every motion.
#
# Usage: bash benches/cell.sh [OUT_DIR] [SETUP MOTION.csv...]
#   default: the robot-level inspection setup over the five bundled Viper motions.
# The binary is copied first, so that a build running meanwhile cannot change it.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-target/cell_bench}"
shift || true
mkdir -p "$out"
cargo build --release --quiet
bin="$out/cable-dict"
cp target/release/cable-dict "$bin"
if [ "$#" -eq 0 ]; then
  set -- robots/viper_s850/inspection.toml motions/viper_s850/{pick_and_place,palletizing,machine_tending,screw_driving,inspection}.csv
fi
setup="$1"; shift
wall() { # wall seconds of a whole command, from GNU time
  /usr/bin/time -f "%e" -o "$out/time" "$@" > /dev/null
  cat "$out/time"
}
singles=()
for motion in "$@"; do
  name="$(basename "$motion" .csv)"
  t="$(wall "$bin" solve --setup "$setup" "$motion" -o "$out/$name.json")"
  singles+=("$name:$t")
done
t_cell="$(wall "$bin" solve --setup "$setup" "$@" -o "$out/cell.json")"
set +e
"$bin" check "$out/cell.json" "$@" > "$out/check.txt"
check_code=$?
set -e
python3 - "$out" "$t_cell" "$check_code" "${singles[@]}" <<'PY'
import json, sys
out, t_cell, check_code = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
rows = [s.rsplit(":", 1) for s in sys.argv[4:]]
def result(name):
    r = json.load(open(f"{out}/{name}.json"))
    return r["status"], r.get("total_length_mm")
times = []
for name, t in rows:
    status, length = result(name)
    times.append(float(t))
    print(f"{name:18s} {status:9s} {length} mm  {float(t):7.2f} s")
status, length = result("cell")
print(f"{'cell':18s} {status:9s} {length} mm  {t_cell:7.2f} s: "
      f"{t_cell / max(times):.1f}x the slowest single solve, {t_cell / sum(times):.2f}x their sum; "
      f"check of its mounting: exit {check_code}")
PY
