#!/usr/bin/env bash
# The paper comparison (its Tables 7–10): both bundled motions solved with the previous
# method (straight cable dragged into place and relaxed in rapier3d, one guide per link),
# method 1 (Hermite + quasi-static solver, one guide per link) and method 2 (intra-link
# segments too); prints a Markdown table of set sizes, results and stage times.
# Each motion is solved with the paper's Table 3 cables (cables/*_paper.toml: the bundled
# setups copied with their cable swapped and their paths made absolute) and with the
# realistic presets the bundled setups use.
#
# Usage: bash benches/paper_comparison.sh [OUT_DIR] [METHOD...]
#   OUT_DIR  where the result JSON files go (default target/paper_comparison)
#   METHOD   any of previous, 1, 2 (default: all three). The previous method takes about
#            0.3 s per static solve: tens of minutes per motion on two cores.
# Needs jq. Times are wall-clock on this machine; run nothing else meanwhile.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-target/paper_comparison}
shift || true
methods=("$@")
[ ${#methods[@]} -eq 0 ] && methods=(previous 1 2)
mkdir -p "$out"
cargo build --release --quiet
bin=target/release/cable-dict
root=$PWD
for motion in pick_and_place inspection; do
  sed -e "s|^robot = \"|robot = \"$root/robots/viper_s850/|" \
      -e "s|^cable = \"../../cables/\(.*\)\.toml\"|cable = \"$root/cables/\1_paper.toml\"|" \
      "robots/viper_s850/$motion.toml" > "$out/$motion-paper.toml"
  cp "robots/viper_s850/$motion.toml" "$out/$motion-realistic.toml"
  sed -i -e "s|^robot = \"|robot = \"$root/robots/viper_s850/|" \
      -e "s|^cable = \"../../cables/|cable = \"$root/cables/|" "$out/$motion-realistic.toml"
done
cables=(paper realistic)

for motion in pick_and_place inspection; do
  for cable in "${cables[@]}"; do
  for method in "${methods[@]}"; do
    case $method in
      previous) args=(--connect linear --max-guides-per-link 1) ;;
      1) args=(--max-guides-per-link 1) ;;
      2) args=(--max-guides-per-link 2) ;;
      *) echo "unknown method $method (previous, 1 or 2)" >&2; exit 2 ;;
    esac
    echo "solving $motion ($cable cable) with method $method …" >&2
    "$bin" -q solve --setup "$out/$motion-$cable.toml" "motions/viper_s850/$motion.csv" \
      "${args[@]}" --json -o "$out/$motion-$cable-$method.json" > /dev/null
  done
  done
done

echo "| motion | cable | method | \|D1\| C1 / C2 / C3 / C4 | \|D2\| C1 / C2 / C3 / C4 | \|D3\| | result | length (mm) | motion tests | attachment (s) | static sweep (s) | motion test (s) | total (s) |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for motion in pick_and_place inspection; do
  for cable in "${cables[@]}"; do
  for method in "${methods[@]}"; do
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
