#!/usr/bin/env bash
# Regenerates the command outputs shown in README.md and docs/*.md, and the README's picture.
#
#   bash scripts/regenerate-docs.sh           rewrite every generated block and the picture
#   bash scripts/regenerate-docs.sh --check   regenerate into a temporary copy; print a unified
#                                             diff and the file name of whatever differs
#
# A generated block is a marker line naming a command, immediately followed by a fenced
# ```text block that holds the command's standard output:
#
#   <!-- generated: cable-dict robot-info robots/viper_s850/viper_s850.urdf -->
#   ```text
#   …
#   ```
#
# The command runs with bash (`set -o pipefail`) from the repository root, standard input
# empty, with `cable-dict` meaning the binary under test; it must exit 0 and print something.
# The repository's absolute path in its output is written `…` (so the block is the same in
# every clone). Markers inside fenced code are ignored. Only mark commands whose standard
# output is byte-identical from run to run and at any thread count (no timings).
#
# The picture docs/images/pick-and-place.svg is pose-1.svg of the report of the README's
# first run (`cable-dict solve --setup robots/viper_s850/pick_and_place.toml
# motions/viper_s850/pick_and_place.csv --report DIR`): the cable on the robot at the
# motion's first critical pose, the installation pose, in front, side and top views.
#
# Binary: $CABLE_DICT if set, else target/release/cable-dict (`cargo build --release`).
# Exit status: 0 written, or (--check) everything up to date; 1 (--check) a file differs, or
# a marked command failed or printed nothing (nothing is written then); 2 it cannot run: no
# binary, a bad argument, a marker without its fenced block.
set -euo pipefail

usage() {
    echo "usage: bash scripts/regenerate-docs.sh [--check]" >&2
}

mode="write"
if [ $# -gt 1 ]; then
    usage
    exit 2
fi
case "${1-}" in
    "") ;;
    --check) mode=check ;;
    -h | --help)
        sed -n '2,/^set -euo/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'
        exit 0
        ;;
    *)
        usage
        exit 2
        ;;
esac

# The binary, absolute, resolved from where the script was called.
bin=${CABLE_DICT:-}
root=$(cd "$(dirname "$0")/.." && pwd -P)
if [ -z "$bin" ]; then
    bin=$root/target/release/cable-dict
elif [ "${bin#/}" = "$bin" ]; then
    bin=$PWD/$bin
fi
if [ ! -f "$bin" ] || [ ! -x "$bin" ]; then
    echo "regenerate-docs: no cable-dict binary at $bin: run \`cargo build --release\` or set CABLE_DICT" >&2
    exit 2
fi
cd "$root"

tmp=$(mktemp -d "${TMPDIR:-/tmp}/regenerate-docs.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/bin" "$tmp/old/docs/images" "$tmp/new/docs/images"
ln -s "$bin" "$tmp/bin/cable-dict"

# Markers and fences. A marker must be the whole line; a fence opens with 3 or more backticks
# or tildes and closes with at least as many of the same, nothing after them.
re_marker='^([[:space:]]*)<!--[[:space:]]+generated:[[:space:]]*([^[:space:]].*[^[:space:]])[[:space:]]+-->[[:space:]]*$'
re_marker_like='^[[:space:]]*<!--[[:space:]]*generated'
re_fence='^([[:space:]]*)(```+|~~~+)[[:space:]]*([^[:space:]]*)'
re_close='^[[:space:]]*(```+|~~~+)[[:space:]]*$'

die() { # file:line message — the input cannot be processed
    echo "regenerate-docs: $*" >&2
    exit 2
}

failed=0 # a marked command failed: nothing is written

# run FILE LINE COMMAND: the command's standard output, root path shortened, into $tmp/out.
run() {
    local file=$1 line=$2 cmd=$3 status=0
    (PATH="$tmp/bin:$PATH" bash -o pipefail -c "$cmd" </dev/null >"$tmp/out" 2>"$tmp/err") || status=$?
    if [ "$status" -ne 0 ]; then
        echo "regenerate-docs: $file:$line: exit status $status from: $cmd" >&2
        sed 's/^/    /' "$tmp/err" >&2
        failed=1
        return 1
    fi
    if [ ! -s "$tmp/out" ]; then
        echo "regenerate-docs: $file:$line: no output on standard output from: $cmd" >&2
        failed=1
        return 1
    fi
    return 0
}

# regenerate FILE: writes $tmp/new/FILE.
regenerate() {
    local file=$1 out=$tmp/new/$1
    local -a lines output
    local n i j line indent cmd open fence_char fence_len info text o
    mapfile -t lines <"$file"
    n=${#lines[@]}
    : >"$out"
    i=0
    open="" # the opening fence of the code block we are in, if any
    while [ "$i" -lt "$n" ]; do
        line=${lines[i]}
        if [ -n "$open" ]; then
            if [[ $line =~ $re_close ]] && [ "${BASH_REMATCH[1]:0:1}" = "${open:0:1}" ] &&
                [ "${#BASH_REMATCH[1]}" -ge "${#open}" ]; then
                open=""
            fi
            printf '%s\n' "$line" >>"$out"
            i=$((i + 1))
            continue
        fi
        if [[ $line =~ $re_fence ]]; then
            open=${BASH_REMATCH[2]}
            printf '%s\n' "$line" >>"$out"
            i=$((i + 1))
            continue
        fi
        if ! [[ $line =~ $re_marker_like ]]; then
            printf '%s\n' "$line" >>"$out"
            i=$((i + 1))
            continue
        fi
        # A generated block.
        [[ $line =~ $re_marker ]] ||
            die "$file:$((i + 1)): a marker is one whole line: <!-- generated: COMMAND -->"
        indent=${BASH_REMATCH[1]}
        cmd=${BASH_REMATCH[2]}
        j=$((i + 1))
        if [ "$j" -ge "$n" ] || ! [[ ${lines[j]} =~ $re_fence ]]; then
            die "$file:$((i + 1)): the marker is not immediately followed by a \`\`\`text fence"
        fi
        fence_char=${BASH_REMATCH[2]:0:1}
        fence_len=${#BASH_REMATCH[2]}
        info=${BASH_REMATCH[3]}
        [ "$info" = text ] ||
            die "$file:$((j + 1)): the block after a marker must be \`\`\`text, not \`\`\`$info"
        # Its closing fence.
        j=$((j + 1))
        while [ "$j" -lt "$n" ]; do
            if [[ ${lines[j]} =~ $re_close ]] && [ "${BASH_REMATCH[1]:0:1}" = "$fence_char" ] &&
                [ "${#BASH_REMATCH[1]}" -ge "$fence_len" ]; then
                break
            fi
            j=$((j + 1))
        done
        [ "$j" -lt "$n" ] || die "$file:$((i + 2)): the \`\`\`text block after the marker is not closed"
        printf '%s\n%s\n' "$line" "${lines[i + 1]}" >>"$out"
        if run "$file" "$((i + 1))" "$cmd"; then
            text=$(
                cat "$tmp/out"
                printf x
            )
            text=${text%x}
            text=${text//"$root/"/…/}
            text=${text//"$root"/…}
            mapfile -t output <<<"${text%$'\n'}"
            for o in "${output[@]}"; do
                if [[ $o =~ $re_close ]] && [ "${BASH_REMATCH[1]:0:1}" = "$fence_char" ] &&
                    [ "${#BASH_REMATCH[1]}" -ge "$fence_len" ]; then
                    die "$file:$((i + 2)): the output has a line that closes the fence; use a longer fence"
                fi
                if [ -n "$o" ]; then
                    printf '%s%s\n' "$indent" "$o" >>"$out"
                else
                    printf '\n' >>"$out"
                fi
            done
        fi
        printf '%s\n' "${lines[j]}" >>"$out"
        i=$((j + 1))
    done
}

# The files: Markdown with generated blocks, and the picture.
files=(README.md)
for f in docs/*.md; do
    files+=("$f")
done
picture=docs/images/pick-and-place.svg

for f in "${files[@]}"; do
    mkdir -p "$tmp/old/$(dirname "$f")"
    cp "$f" "$tmp/old/$f" # what was read, to write back only over an unchanged file
    regenerate "$f"
done

# The picture: pose-1.svg of the first run's report.
report=$tmp/report
if (PATH="$tmp/bin:$PATH" cable-dict solve --setup robots/viper_s850/pick_and_place.toml \
    motions/viper_s850/pick_and_place.csv --report "$report" </dev/null >/dev/null 2>"$tmp/err"); then
    if [ -f "$report/pose-1.svg" ]; then
        cp "$report/pose-1.svg" "$tmp/new/$picture"
    else
        echo "regenerate-docs: the pick-and-place report has no pose-1.svg for $picture; it has: $(cd "$report" && echo ./*)" >&2
        failed=1
    fi
else
    echo "regenerate-docs: the pick-and-place solve --report for $picture failed:" >&2
    sed 's/^/    /' "$tmp/err" >&2
    failed=1
fi
if [ -f "$picture" ]; then
    cp "$picture" "$tmp/old/$picture"
fi
files+=("$picture")

if [ "$failed" -ne 0 ]; then
    echo "regenerate-docs: a marked command failed (above); nothing written" >&2
    exit 1
fi

changed=()
for f in "${files[@]}"; do
    if ! cmp -s "$f" "$tmp/new/$f" 2>/dev/null; then
        changed+=("$f")
    fi
done

if [ "$mode" = check ]; then
    if [ "${#changed[@]}" -eq 0 ]; then
        echo "regenerate-docs: README.md, docs/*.md and $picture are up to date"
        exit 0
    fi
    for f in "${changed[@]}"; do
        old=$f
        [ -f "$f" ] || old=/dev/null
        diff -u --label "a/$f" --label "b/$f" "$old" "$tmp/new/$f" || true
    done
    for f in "${changed[@]}"; do
        echo "regenerate-docs: out of date: $f" >&2
    done
    echo "regenerate-docs: run \`bash scripts/regenerate-docs.sh\` and commit the result" >&2
    exit 1
fi

if [ "${#changed[@]}" -eq 0 ]; then
    echo "regenerate-docs: nothing to change"
    exit 0
fi
skipped=0
for f in "${changed[@]}"; do
    # Someone else's edit since we read the file wins: run again then.
    if [ -f "$tmp/old/$f" ] && ! cmp -s "$f" "$tmp/old/$f"; then
        echo "regenerate-docs: $f changed while it was regenerated; not written, run again" >&2
        skipped=1
        continue
    fi
    mkdir -p "$(dirname "$f")"
    cat "$tmp/new/$f" >"$f"
    echo "regenerate-docs: updated $f"
done
exit "$skipped"
