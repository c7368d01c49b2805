#!/usr/bin/env bash
# solve --dict against solve --setup in one run: wall times of the whole solve, of the
# attachment test and of its intra-link segments (from the result JSONs), their ratios, and
# whether both found the same path and intra-link sets.
#
# Usage: bash benches/dictionary_speedup.sh [OUT_DIR] [SETUP DICT MOTION ...]
#   default: the hand-written setups with the shipped dictionaries on their motions.
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
  name="$(basename "$setup" .toml)-$(basename "$motion" .csv)"
  "$bin" solve --setup "$setup" "$motion" -o "$out/$name.setup.json" > /dev/null
  "$bin" solve --dict "$dict" --setup "$setup" "$motion" -o "$out/$name.dict.json" > /dev/null
  python3 - "$out/$name.setup.json" "$out/$name.dict.json" "$name" <<'PY'
import json, sys
s, d = (json.load(open(p)) for p in sys.argv[1:3])
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
