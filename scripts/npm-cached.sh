# Sourced by the scripts that run an npm package: `npm_cached PACKAGE VERSION CACHE` installs
# PACKAGE@VERSION into the folder CACHE (its node_modules) unless it is there already; returns
# non-zero when npm fails.
npm_cached() {
    if [ ! -f "$3/node_modules/$1/package.json" ]; then
        mkdir -p "$3"
        echo "installing $1@$2 into $3" >&2
        npm install --prefix "$3" --no-audit --no-fund --silent "$1@$2" >&2
    fi
}
