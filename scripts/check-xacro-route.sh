#!/bin/sh
# CI: the xacro route of docs/robots.md ("Xacro packages") on a real description, no ROS.
#   scripts/check-xacro-route.sh
# Expands the upstream KUKA KR 6 R900 sixx xacro committed unchanged in
# tests/data/robots/kuka_kr6_support/urdf/kr6r900sixx.xacro (it includes its macro and
# kuka_resources' files through `$(find …)`) with scripts/expand-xacro.sh into a package
# folder whose meshes/ is the committed one, loads the result with
# `target/release/cable-dict robot-info --json` (`package://` meshes included) and compares
# it with the hand-expanded tests/data/robots/kuka_kr6_support/urdf/kr6r900sixx.urdf: the
# same link names, joint names, joint limits, and everything else robot-info reports (joint
# origins and axes, collision shapes with the same mesh files and measures), and
# `cable-dict fk --json` poses of every link, the end effector tool0 named, equal within
# 1e-9 m (and 1e-9 in each rotation entry) at two joint vectors.
# Then a stranger's xacros that would copy this machine into the URDF — `$(env …)`,
# `$(optenv …)`, an include and a YAML file outside the package — are refused, and
# --allow-machine expands `$(env HOME)`.
# CABLE_DICT (default target/release/cable-dict) is the binary checked.
# Exit status: 0 the same robot, 1 a difference (each printed), 2 could not check.
set -eu
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="${CABLE_DICT:-$root/target/release/cable-dict}"
[ -x "$bin" ] || { echo "$0: no binary at $bin (cargo build --release)" >&2; exit 2; }
command -v python3 > /dev/null || { echo "$0: python3 is needed" >&2; exit 2; }
package="$root/tests/data/robots/kuka_kr6_support"
xacro_file="$package/urdf/kr6r900sixx.xacro"
reference="$package/urdf/kr6r900sixx.urdf"

work="$(mktemp -d "${TMPDIR:-/tmp}/check-xacro-route.XXXXXX")"
trap 'rm -rf "$work"' EXIT
trap 'exit 130' INT TERM
# The expanded URDF goes where the user's would: in a package folder kuka_kr6_support/urdf,
# beside that package's meshes/, so that package://kuka_kr6_support/meshes/… is found by
# walking up from it.
mkdir -p "$work/kuka_kr6_support/urdf"
ln -s "$package/meshes" "$work/kuka_kr6_support/meshes"
expanded="$work/kuka_kr6_support/urdf/kr6r900sixx.urdf"

status=0
sh "$root/scripts/expand-xacro.sh" "$xacro_file" "$expanded" || status=$?
case "$status" in
    0) ;;
    2) echo "$0: could not expand $xacro_file (see above)" >&2; exit 2 ;;
    *) echo "FAIL: scripts/expand-xacro.sh refused $xacro_file (see above)" >&2; exit 1 ;;
esac

# Two joint vectors within the limits, degrees for joint_a1 … joint_a6 (restated below).
fk1=0,0,0,0,0,0
fk2=30,-60,45,90,-45,120
# robot-info and fk at both joint vectors of the URDF $2, into $work/$1.*.json.
measure() {
    if ! { "$bin" -q robot-info "$2" --json > "$work/$1.info.json" \
        && "$bin" -q fk --json --joints-deg "$fk1" "$2" > "$work/$1.fk1.json" \
        && "$bin" -q fk --json --joints-deg "$fk2" "$2" > "$work/$1.fk2.json"; }; then
        echo "FAIL: cable-dict refused the $1 URDF $2 (see above)" >&2
        exit 1
    fi
}
measure expanded "$expanded"
measure reference "$reference"

python3 - "$work" << 'EOF'
import json
import os
import sys

work = sys.argv[1]
TOLERANCE = 1e-9
problems = []


def load(name):
    with open(os.path.join(work, name)) as f:
        return json.load(f)


def normalised(info):
    """robot-info's JSON without what names the URDF's own place: the source file, and mesh
    files by the path they were found at (both resolve to the same committed file)."""
    info = dict(info)
    info.pop("source", None)
    for link in info.get("links", []):
        for collider in link.get("colliders") or []:
            mesh = collider.get("mesh")
            if mesh and "file" in mesh:
                real = os.path.realpath(mesh["file"])
                collider["description"] = collider["description"].replace(mesh["file"], real)
                mesh["file"] = real
    return info


def differences(a, b, where):
    if isinstance(a, dict) and isinstance(b, dict):
        for key in sorted(set(a) | set(b)):
            if key not in a or key not in b:
                yield "%s.%s: only in the %s" % (where, key, "expanded" if key in a else "reference")
            else:
                yield from differences(a[key], b[key], "%s.%s" % (where, key))
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            yield "%s: %d entries vs %d" % (where, len(a), len(b))
        for i, (x, y) in enumerate(zip(a, b)):
            yield from differences(x, y, "%s[%d]" % (where, i))
    elif isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        if abs(a - b) > TOLERANCE:
            yield "%s: %r vs %r" % (where, a, b)
    elif a != b:
        yield "%s: %r vs %r" % (where, a, b)


expanded, reference = load("expanded.info.json"), load("reference.info.json")

# The three things named first, with messages of their own.
names = lambda items: [item["name"] for item in items]
if names(expanded["links"]) != names(reference["links"]):
    problems.append("link names: %s vs %s" % (names(expanded["links"]), names(reference["links"])))
if names(expanded["joints"]) != names(reference["joints"]):
    problems.append("joint names: %s vs %s" % (names(expanded["joints"]), names(reference["joints"])))
limits = lambda joints: {j["name"]: [j.get(k) for k in ("lower", "upper", "velocity")] for j in joints}
lim_e, lim_r = limits(expanded["joints"]), limits(reference["joints"])
for joint in sorted(set(lim_e) & set(lim_r)):
    for what in differences(lim_e[joint], lim_r[joint], "joint %s limits [lower, upper, velocity]" % joint):
        problems.append(what)
# Then everything else robot-info reports.
problems.extend("robot-info " + d for d in differences(normalised(expanded), normalised(reference), ""))

JOINTS_DEG = {"fk1": "0,0,0,0,0,0", "fk2": "30,-60,45,90,-45,120"}
for case, joints in JOINTS_DEG.items():
    by_name = lambda fk: {link["name"]: link for link in fk["links"]}
    fk_e = by_name(load("expanded.%s.json" % case))
    fk_r = by_name(load("reference.%s.json" % case))
    problems.extend("fk at %s deg: link %s" % (joints, d[1:]) for d in differences(fk_e, fk_r, ""))
    if "tool0" not in fk_e:
        problems.append("fk at %s deg: no link tool0 in the expanded robot" % joints)
    else:
        position = ", ".join("%.6f" % c for c in fk_e["tool0"]["position_m"])
        print("fk at %s deg: tool0 at (%s) m" % (joints, position))

if problems:
    print("FAIL: the robot expanded from kr6r900sixx.xacro differs from kr6r900sixx.urdf:")
    for problem in problems:
        print("  " + problem)
    sys.exit(1)
dof = expanded["dof"]
print("xacro route: kr6r900sixx.xacro expanded without ROS is the committed kr6r900sixx.urdf "
      "(%d links, %d joints of which %d actuated, limits, robot-info, fk of every link at two "
      "joint vectors within %g m)" % (len(expanded["links"]), len(expanded["joints"]), dof, TOLERANCE))
EOF

# A stranger's xacro may not copy this machine into the URDF: `$(env …)`, `$(optenv …)`, an
# include and a YAML file outside its package are refused (exit 1, the
# refusal named), and --allow-machine allows what the user trusts.
hostile="$work/stranger/urdf"
mkdir -p "$hostile"
echo "secret: 1" > "$work/secret.yaml"
echo '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="outside"/></robot>' > "$work/outside.xacro"
wrap() { printf '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">%s</robot>\n' "$1"; }
wrap '<link name="$(env HOME)"/>' > "$hostile/env.xacro"
wrap '<link name="$(optenv HOME nobody)"/>' > "$hostile/optenv.xacro"
wrap '<xacro:include filename="../../outside.xacro"/>' > "$hostile/include.xacro"
wrap "<xacro:property name=\"y\" value=\"\${xacro.load_yaml('$work/secret.yaml')}\"/><link name=\"l\${y['secret']}\"/>" > "$hostile/yaml.xacro"
for case in env:environment optenv:environment include:outside yaml:outside; do
    name="${case%%:*}" words="${case#*:}"
    status=0
    message="$(sh "$root/scripts/expand-xacro.sh" "$hostile/$name.xacro" "$work/$name.urdf" 2>&1)" || status=$?
    if [ "$status" -ne 1 ] || ! printf '%s' "$message" | grep -q "$words" || [ -e "$work/$name.urdf" ]; then
        echo "FAIL: a xacro reading this machine ($name) was not refused (exit $status): $message" >&2
        exit 1
    fi
done
sh "$root/scripts/expand-xacro.sh" --allow-machine "$hostile/env.xacro" "$work/env.urdf" \
    || { echo "FAIL: --allow-machine refused \$(env HOME)" >&2; exit 1; }
grep -q "name=\"$HOME\"" "$work/env.urdf" || { echo "FAIL: --allow-machine did not expand \$(env HOME)" >&2; exit 1; }
echo "xacro route: \$(env), \$(optenv), an include and a YAML file outside the package refused; --allow-machine allows them"
