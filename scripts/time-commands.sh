#!/usr/bin/env bash
# Times whole commands as processes, in turn, and prints each one's median wall time, its
# peak memory and (for two or more) each time's ratio to the first's:
#
#   bash scripts/time-commands.sh RUNS 'COMMAND A' ['COMMAND B' ...]
#
# The commands run RUNS times each, interleaved (A B A B …), so that both see the same
# machine; their output is discarded, a failing command stops the script. Uses
# /usr/bin/time (GNU time: apt-get install time).
set -euo pipefail
if [ $# -lt 2 ] || ! [[ $1 =~ ^[1-9][0-9]*$ ]]; then
    echo "usage: $0 RUNS 'COMMAND' ['COMMAND' ...]" >&2
    exit 2
fi
runs=$1
shift
[ -x /usr/bin/time ] || { echo "$0: /usr/bin/time (GNU time) is needed" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for ((r = 0; r < runs; r++)); do
    for ((c = 1; c <= $#; c++)); do
        /usr/bin/time -f '%e %M' -o "$out/$c.$r" bash -c "${!c}" > /dev/null 2>&1 || {
            echo "$0: command $c failed: ${!c}" >&2
            exit 1
        }
    done
done
first=""
for ((c = 1; c <= $#; c++)); do
    median=$(cat "$out/$c".* | awk '{print $1}' | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}')
    peak=$(cat "$out/$c".* | awk '{print $2}' | sort -g | tail -1)
    ratio=""
    if [ -z "$first" ]; then first=$median; else ratio=$(awk -v a="$median" -v b="$first" 'BEGIN {printf "  ratio to the first %.2f", a / b}'); fi
    printf '%8.3f s  %7.1f MB%s  %s\n' "$median" "$(awk -v k="$peak" 'BEGIN {print k / 1024}')" "$ratio" "${!c}"
done
