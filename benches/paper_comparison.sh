#!/usr/bin/env bash
# The paper comparison (its Tables 7–10): every bundled motion solved with the previous
# method (straight cable dragged into place and relaxed in rapier3d, one guide per link),
# method 1 (Hermite + quasi-static solver, one guide per link) and method 2 (intra-link
# segments too); prints a Markdown table of set sizes, results and stage times.
# The gripper motions (pick_and_place, palletizing, machine_tending, screw_driving) use the
# robot-level setup robots/viper_s850/pick_and_place.toml, the inspection motion
# robots/viper_s850/inspection.toml; each is solved with the paper's Table 3 cables
# (cables/*_paper.toml: the setups copied with their cable swapped and their paths made
# absolute) and with the realistic presets the setups use.
#
# Usage: bash benches/paper_comparison.sh [OUT_DIR] [METHOD...]
#   OUT_DIR  where the result JSON files go (default target/paper_comparison)
#   METHOD   any of previous, 1, 2 (default: all three). The previous method takes about
#            0.3 s per static solve, days for a generated catalogue: `previous` runs its
#            attachment test on a sample (benches/previous_method_sample.toml, 176 pieces of
#            C1) with both connect methods and extrapolates each motion's method-1 run from
#            the sample's time per evaluated piece (needs method 1 in the same run).
# Needs jq. Times are wall-clock on this machine; run nothing else meanwhile.
# REUSE=1 keeps the result JSONs already in OUT_DIR (to reprint the table).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-target/paper_comparison}
shift || true
methods=("$@")
[ ${#methods[@]} -eq 0 ] && methods=(previous 1 2)
mkdir -p "$out"
cargo build --release --quiet
# A copy: a build started meanwhile must not swap the binary under the runs.
bin="$out/cable-dict"
cp target/release/cable-dict "$bin"
root=$PWD
setup_of() { case $1 in inspection) echo inspection ;; *) echo pick_and_place ;; esac; }
motions=(pick_and_place palletizing machine_tending screw_driving inspection)
for motion in pick_and_place inspection; do
  sed -e "s|^robot = \"|robot = \"$root/robots/viper_s850/|" \
      -e "s|^cable = \"../../cables/\(.*\)\.toml\"|cable = \"$root/cables/\1_paper.toml\"|" \
      "robots/viper_s850/$motion.toml" > "$out/$motion-paper.toml"
  cp "robots/viper_s850/$motion.toml" "$out/$motion-realistic.toml"
  sed -i -e "s|^robot = \"|robot = \"$root/robots/viper_s850/|" \
      -e "s|^cable = \"../../cables/|cable = \"$root/cables/|" "$out/$motion-realistic.toml"
done
cables=(paper realistic)

for motion in "${motions[@]}"; do
  for cable in "${cables[@]}"; do
  for method in "${methods[@]}"; do
    case $method in
      previous) continue ;;
      1) args=(--max-guides-per-link 1) ;;
      2) args=(--max-guides-per-link 2) ;;
      *) echo "unknown method $method (previous, 1 or 2)" >&2; exit 2 ;;
    esac
    json="$out/$motion-$cable-$method.json"
    [ -n "${REUSE:-}" ] && [ -f "$json" ] && continue
    echo "solving $motion ($cable cable) with method $method …" >&2
    "$bin" -q solve --setup "$out/$(setup_of "$motion")-$cable.toml" "motions/viper_s850/$motion.csv" \
      "${args[@]}" --json -o "$json" > /dev/null
  done
  done
done

echo "| motion | cable | method | \|D1\| C1 / C2 / C3 / C4 | \|D2\| C1 / C2 / C3 / C4 | \|D3\| | result | length (mm) | motion tests | attachment (s) | static sweep (s) | motion test (s) | total (s) |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for motion in "${motions[@]}"; do
  for cable in "${cables[@]}"; do
  for method in "${methods[@]}"; do
    [ "$method" = previous ] && continue
    jq -r --arg motion "$motion" --arg cable "$cable" '
      def sizes(k): [.sets[] | .[k] | tostring] | join(" / ");
      def result: if .outcome == "solved" then "solved"
        elif .outcome == "no_chain" then "none (no chain)"
        elif .outcome == "none_passed_motion_test" then "unsolved (motion test)"
        else .outcome end;
      def secs(x): (x * 100 | round) / 100 | tostring;
      "| \($motion) | \($cable) | \(.method) | \(sizes("d1")) | \(sizes("d2")) | \(.chains) | \(result) | \(.total_length_mm // "-") | \(.motion_test.candidates_tried // "-") | \(secs(.timings_s.attachment)) | \(secs(.timings_s.static_sweep)) | \(secs(.timings_s.motion_test)) | \(secs(.timings_s.total)) |"
    ' "$out/$motion-$cable-$method.json"
  done
  done
done

# The previous method on a sample, extrapolated: seconds per evaluated piece × evaluations.
if printf '%s\n' "${methods[@]}" | grep -qx previous; then
  for connect in linear hermite; do
    [ -n "${REUSE:-}" ] && [ -f "$out/previous-sample-$connect.json" ] && continue
    echo "previous-method sample with --connect $connect …" >&2
    "$bin" -q solve --setup benches/previous_method_sample.toml motions/viper_s850/pick_and_place.csv \
      --connect "$connect" --max-guides-per-link 1 --no-motion-test --json \
      -o "$out/previous-sample-$connect.json" > /dev/null
  done
  per_piece() { jq '.timings_s.attachment / ([.sets[].evaluations] | add)' "$out/previous-sample-$1.json"; }
  linear=$(per_piece linear)
  hermite=$(per_piece hermite)
  echo
  echo "previous method, sample of 176 pieces of C1: $(jq '.timings_s.attachment' "$out/previous-sample-linear.json") s" \
       "($linear s per evaluated piece) against $(jq '.timings_s.attachment' "$out/previous-sample-hermite.json") s" \
       "with method 1's solver ($hermite s per piece)"
  echo
  echo "| motion | cable | evaluated pieces (method 1) | method 1 attachment (s) | previous method, extrapolated (h) |"
  echo "| --- | --- | --- | --- | --- |"
  for motion in "${motions[@]}"; do
    for cable in "${cables[@]}"; do
      json="$out/$motion-$cable-1.json"
      [ -f "$json" ] || continue
      jq -r --arg motion "$motion" --arg cable "$cable" --argjson per "$linear" '
        ([.sets[].evaluations] | add) as $n |
        "| \($motion) | \($cable) | \($n) | \((.timings_s.attachment * 100 | round) / 100) | \(($n * $per / 3600 * 10 | round) / 10) |"
      ' "$json"
    done
  done
fi
