#!/usr/bin/env bash
# solve --dict against solve --setup on both bundled motions, in one run: wall times of the
# whole solve and of the attachment test (from the result JSON), and their ratios.
#
# Usage: bash benches/dictionary_speedup.sh [OUT_DIR]   (default target/dictionary_speedup)
# Needs the shipped dictionaries in dictionaries/ (or rebuild them, README "Dictionaries").
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-target/dictionary_speedup}"
mkdir -p "$out"
cargo build --release --quiet
bin=target/release/cable-dict

field() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(d$2)" "$1"; }

printf '%-16s %-8s %10s %12s %10s\n' motion mode "total s" "attachment s" status
for name in pick_and_place inspection; do
  setup="robots/viper_s850/hand_written/$name.toml"
  motion="motions/viper_s850/$name.csv"
  dict="dictionaries/viper_s850_$name.cdict"
  "$bin" solve --setup "$setup" "$motion" -o "$out/$name.setup.json" > /dev/null
  "$bin" solve --dict "$dict" "$motion" -o "$out/$name.dict.json" > /dev/null
  for mode in setup dict; do
    json="$out/$name.$mode.json"
    printf '%-16s %-8s %10.2f %12.2f %10s\n' "$name" "$mode" \
      "$(field "$json" "['timings_s']['total']")" \
      "$(field "$json" "['timings_s']['attachment']")" \
      "$(field "$json" "['status']")"
  done
  python3 - "$out/$name.setup.json" "$out/$name.dict.json" "$name" <<'PY'
import json, sys
s, d = (json.load(open(p))["timings_s"] for p in sys.argv[1:3])
print(f"{sys.argv[3]:<16} dict/setup: total {d['total'] / s['total']:.0%}, "
      f"attachment {d['attachment'] / s['attachment']:.0%}")
PY
done
