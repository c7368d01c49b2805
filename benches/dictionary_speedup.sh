#!/usr/bin/env bash
# solve --dict against solve --setup in one run: wall times of the whole solve, of the
# attachment test and of its intra-link segments (from the result JSONs), their ratios, and
# whether both found the same path and intra-link sets.
#
# Usage: bash benches/dictionary_speedup.sh [OUT_DIR] [SETUP DICT MOTION ...]
#   default: the hand-written setups with the shipped dictionaries on their motions.
#   MOTION may be --ranges=RANGES.toml: a design for axis ranges instead of a motion (its
#   whole wall time counts every box it tried; benches/range_dictionary.sh runs one).
# The binary is copied first, so that a build running meanwhile cannot change it.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-target/dictionary_speedup}"
shift || true
mkdir -p "$out"
cargo build --release --quiet
bin="$out/cable-dict"
cp target/release/cable-dict "$bin"
if [ "$#" -eq 0 ]; then
  set -- robots/viper_s850/hand_written/pick_and_place.toml dictionaries/viper_s850_pick_and_place.cdict motions/viper_s850/pick_and_place.csv \
         robots/viper_s850/hand_written/inspection.toml dictionaries/viper_s850_inspection.cdict motions/viper_s850/inspection.csv
fi
while [ "$#" -ge 3 ]; do
  setup="$1" dict="$2" motion="$3"; shift 3
  case "$motion" in
    --ranges=*) asked=(--ranges "${motion#--ranges=}"); motion="${motion#--ranges=}" ;;
    *) asked=("$motion") ;;
  esac
  name="$(basename "$setup" .toml)-$(basename "$(basename "$motion" .csv)" .toml)"
  t0=$(date +%s.%N)
  "$bin" -q solve --setup "$setup" "${asked[@]}" -o "$out/$name.setup.json" > /dev/null
  t1=$(date +%s.%N)
  "$bin" -q solve --dict "$dict" --setup "$setup" "${asked[@]}" -o "$out/$name.dict.json" > /dev/null
  t2=$(date +%s.%N)
  python3 - "$out/$name.setup.json" "$out/$name.dict.json" "$name" "$t0" "$t1" "$t2" <<'PY'
import json, sys
s, d = (json.load(open(p)) for p in sys.argv[1:3])
t0, t1, t2 = (float(t) for t in sys.argv[4:7])
print(f"{sys.argv[3]}: whole process {t1 - t0:.2f} s -> {t2 - t1:.2f} s ({(t1 - t0) / (t2 - t1):.2f}x)")
def intra(r):
    return r["timings_s"]["attachment_intra_link"]
def sets(r):
    return [(x["segment"], x["d1"], x["d2"]) for x in r["sets"] if x["kind"] == "intra-link"]
ts, td = s["timings_s"], d["timings_s"]
print(f"{sys.argv[3]}: total {ts['total']:.2f} s -> {td['total']:.2f} s; "
      f"attachment {ts['attachment']:.2f} s -> {td['attachment']:.2f} s "
      f"({ts['attachment'] / td['attachment']:.1f}x); "
      f"intra-link segments {intra(s):.2f} s -> {intra(d):.3f} s ({intra(s) / max(intra(d), 1e-9):.0f}x); "
      f"same path: {s.get('ecpv') == d.get('ecpv')}, same intra-link sets: {sets(s) == sets(d)}; "
      f"{s['status']} {s.get('total_length_mm')} mm")
PY
done
