#!/bin/sh
# Expands a xacro robot description into a URDF with PyPI's xacro, no ROS needed:
#   scripts/expand-xacro.sh [--allow-machine] IN.xacro OUT.urdf [name:=value …]
# The name:=value arguments go to xacro (the xacro's <xacro:arg>s).
# Expanding a xacro runs its author's macros and Python expressions on this machine. So that
# a stranger's description cannot copy this machine into the URDF (which `cable-dict build`
# then embeds in a dictionary others receive), `$(env …)` and `$(optenv …)` are refused, and
# so is reading a file (an include, a YAML file) outside IN's folder, the folder above it
# (IN's package in the usual pkg/urdf/ layout) and the package folders `$(find …)` found;
# --allow-machine allows both, for a description you trust.
# `$(find pkg)` resolves as cable-dict resolves `package://pkg/…` (docs/robots.md, "Xacro
# packages"): to the first folder, going up from IN's folder, that is called pkg or holds a
# folder pkg. PyPI's xacro asks ROS 2's ament_index_python for it; this script puts a
# stand-in module with that rule first on PYTHONPATH. The upstream files are not changed.
# Installs xacro==XACRO_VERSION (default 2.1.1, the version the test robots were expanded
# with) into a virtualenv in a cache folder (EXPAND_XACRO_CACHE, default
# ${TMPDIR:-/tmp}/cable-dict-xacro) on first use.
# OUT is written whole or not at all: xacro writes a temporary file beside it, renamed to OUT.
# Exit status: 0 expanded, 1 xacro failed on IN (its message printed), 2 usage, or xacro could
# not be installed.
set -eu
allow_machine=0
if [ "${1:-}" = "--allow-machine" ]; then allow_machine=1; shift; fi
[ "$#" -ge 2 ] || { echo "usage: $0 [--allow-machine] IN.xacro OUT.urdf [name:=value …]" >&2; exit 2; }
in="$1"
out="$2"
shift 2
[ -f "$in" ] || { echo "$0: $in is not a file" >&2; exit 2; }
version="${XACRO_VERSION:-2.1.1}"
cache="${EXPAND_XACRO_CACHE:-${TMPDIR:-/tmp}/cable-dict-xacro}"
venv="$cache/xacro-$version"

building=""
work=""
partial=""
trap 'rm -rf "$building" "$work"; rm -f "$partial"' EXIT
trap 'exit 130' INT TERM

# The virtualenv is built in a temporary folder and renamed into place once xacro runs in it,
# so that an interrupted install is not taken for a finished one.
if [ ! -d "$venv" ]; then
    command -v python3 > /dev/null || { echo "$0: python3 is needed to install xacro" >&2; exit 2; }
    mkdir -p "$cache"
    building="$(mktemp -d "$cache/.xacro-$version.XXXXXX")"
    echo "installing xacro==$version into $venv" >&2
    if ! { python3 -m venv "$building" \
        && "$building/bin/python" -m pip install --quiet --disable-pip-version-check "xacro==$version" \
        && "$building/bin/python" -c 'import xacro'; } >&2; then
        echo "$0: could not install xacro==$version (python3 -m venv, then pip install)" >&2
        exit 2
    fi
    # Another run may have finished first: then its copy is kept and this one removed.
    mv -T "$building" "$venv" 2> /dev/null && building=""
fi
# The scripts in the virtualenv's bin/ name the folder it was built in: xacro is run through
# the virtualenv's python and xacro's console entry point, xacro.main.
[ -x "$venv/bin/python" ] || { echo "$0: no python in $venv: remove that folder" >&2; exit 2; }

work="$(mktemp -d "${TMPDIR:-/tmp}/expand-xacro.XXXXXX")"
out_dir="$(dirname "$out")"
mkdir -p "$out_dir"
partial="$(mktemp "$out_dir/.$(basename "$out").XXXXXX")"

mkdir -p "$work/shim/ament_index_python"
: > "$work/shim/ament_index_python/__init__.py"
cat > "$work/shim/ament_index_python/packages.py" << 'EOF'
"""Stand-in for ROS 2's ament_index_python, written by cable-dict's scripts/expand-xacro.sh.

PyPI's xacro resolves $(find pkg) with get_package_share_directory(pkg). Here a package is a
folder, found as cable-dict finds package://pkg: going up from the folder of the file being
expanded, the first folder that is called pkg or holds a folder pkg.
"""
import os


class PackageNotFoundError(LookupError):
    pass


# The package folders found so far: files in them may be read (cable_dict_xacro_guard).
FOUND = []


def get_package_share_directory(package_name, print_warning=True):
    start = os.environ["CABLE_DICT_XACRO_FIND_FROM"]
    folder = start
    while True:
        if os.path.basename(folder) == package_name:
            FOUND.append(folder)
            return folder
        inside = os.path.join(folder, package_name)
        if os.path.isdir(inside):
            FOUND.append(inside)
            return inside
        parent = os.path.dirname(folder)
        if parent == folder:
            raise PackageNotFoundError(
                "$(find %s): no folder named '%s' in %s or any folder above it"
                % (package_name, package_name, start)
            )
        folder = parent
EOF

cat > "$work/shim/cable_dict_xacro_guard.py" << 'EOF'
"""Written by cable-dict's scripts/expand-xacro.sh: what a xacro may read of this machine.

Unless CABLE_DICT_XACRO_ALLOW_MACHINE is 1: $(env ...) and $(optenv ...) are refused, and
xacro opens for reading only files inside the folder of the file expanded, the folder above
it (its package, in the usual pkg/urdf/ layout) and the package folders $(find ...) found
(symbolic links resolved).
"""
import builtins
import os

import xacro
import xacro.substitution_args as substitution
from ament_index_python import packages

if os.environ.get("CABLE_DICT_XACRO_ALLOW_MACHINE") != "1":

    def refuse_environment(*args, **kwargs):
        raise substitution.SubstitutionException(
            "$(env ...) and $(optenv ...) would copy this machine's environment into the "
            "URDF: refused (scripts/expand-xacro.sh --allow-machine, for a xacro you trust)"
        )

    substitution._env = refuse_environment
    substitution._optenv = refuse_environment
    substitution._eval_dict["env"] = refuse_environment
    substitution._eval_dict["optenv"] = refuse_environment

    def inside(path, folder):
        folder = os.path.realpath(folder)
        return path == folder or path.startswith(folder + os.sep)

    def guarded_open(file, mode="r", *args, **kwargs):
        if not any(c in mode for c in "wax+"):
            path = os.path.realpath(file)
            start = os.environ["CABLE_DICT_XACRO_FIND_FROM"]
            allowed = [start, os.path.dirname(start)] + packages.FOUND
            if not any(inside(path, folder) for folder in allowed):
                raise xacro.XacroException(
                    "%s is outside the package of the file expanded and the package "
                    "folders $(find ...) found: refused (scripts/expand-xacro.sh "
                    "--allow-machine, for a xacro you trust)" % file
                )
        return builtins.open(file, mode, *args, **kwargs)

    # xacro's own functions (parse, load_yaml) find `open` in the module first.
    xacro.open = guarded_open
EOF

# The folder the search starts from, absolute and with symbolic links resolved (as cable-dict's).
find_from="$(cd "$(dirname "$in")" && pwd -P)"
if ! PYTHONPATH="$work/shim${PYTHONPATH:+:$PYTHONPATH}" CABLE_DICT_XACRO_FIND_FROM="$find_from" \
    CABLE_DICT_XACRO_ALLOW_MACHINE="$allow_machine" \
    "$venv/bin/python" -c 'import sys, cable_dict_xacro_guard, xacro; sys.argv[0] = "xacro"; sys.exit(xacro.main())' \
    -o "$partial" "$in" "$@"; then
    echo "$0: xacro could not expand $in; $out is left as it was" >&2
    exit 1
fi
# mktemp made it private; OUT gets the permissions of a file the shell creates.
chmod "$(printf '%o' $((0666 & ~0$(umask))))" "$partial"
mv -f "$partial" "$out"
