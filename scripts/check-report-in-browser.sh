#!/bin/sh
# Checks a report folder (`cable-dict solve … --report DIR`) in a real headless browser:
#   scripts/check-report-in-browser.sh DIR
# Loads DIR/index.html from file:// in Chromium and fails when the page logs a console error
# or an uncaught exception, a request fails or leaves the folder, an <img> did not load
# (naturalWidth 0), or a screenshot of a picture is (almost) one uniform colour.
# Installs Debian's chromium package when CHROMIUM (default /usr/bin/chromium) is missing,
# and the npm package playwright-core, which drives that browser and downloads none of its
# own, into a cache folder (CHECK_REPORT_CACHE, default
# ${TMPDIR:-/tmp}/cable-dict-browser-check) on first use.
# Exit status: 0 the page is fine, 1 a problem (each printed), 2 could not check.
set -eu
[ "$#" -eq 1 ] || { echo "usage: $0 REPORT_DIR" >&2; exit 2; }
version="${PLAYWRIGHT_CORE_VERSION:-1.65.1}"
cache="${CHECK_REPORT_CACHE:-${TMPDIR:-/tmp}/cable-dict-browser-check}"
here="$(cd "$(dirname "$0")" && pwd)"
. "$here/npm-cached.sh"
npm_cached playwright-core "$version" "$cache" || { echo "could not install playwright-core" >&2; exit 2; }
chromium="${CHROMIUM:-/usr/bin/chromium}"
if [ ! -x "$chromium" ]; then
    echo "installing Debian's chromium" >&2
    if ! { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium; } >&2; then
        echo "could not install chromium" >&2
        exit 2
    fi
fi
[ -x "$chromium" ] || { echo "no browser at $chromium" >&2; exit 2; }
CHROMIUM="$chromium" PLAYWRIGHT_CORE_DIR="$cache" exec node "$here/check-report-in-browser.mjs" "$1"
