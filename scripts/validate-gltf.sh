#!/bin/sh
# Validates a .glb/.gltf file with the Khronos glTF validator:
#   scripts/validate-gltf.sh FILE.glb
# Installs the npm package gltf-validator into a cache folder on first use
# (GLTF_VALIDATOR_CACHE, default ${TMPDIR:-/tmp}/cable-dict-gltf-validator).
# Exit status: 0 valid (warnings allowed), 1 errors, 2 could not validate.
set -eu
if [ "$#" -ne 1 ]; then
    echo "usage: $0 FILE.glb" >&2
    exit 2
fi
version="${GLTF_VALIDATOR_VERSION:-2.0.0-dev.3.10}"
cache="${GLTF_VALIDATOR_CACHE:-${TMPDIR:-/tmp}/cable-dict-gltf-validator}"
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/npm-cached.sh"
npm_cached gltf-validator "$version" "$cache"
GLTF_VALIDATOR_DIR="$cache" exec node "$here/validate-gltf.mjs" "$1"
