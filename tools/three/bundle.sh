#!/usr/bin/env bash
# Remakes src/animate/three.min.js, the three.js bundle that
# chaplygin::animate inlines into its pages, and src/animate/THREE_LICENSE:
# `npm ci` installs the versions pinned in package-lock.json (three 0.187.0,
# esbuild), esbuild bundles entry.js (three's classes the page uses and
# OrbitControls, on the global THREE) into one minified IIFE, and three's
# licence header is put back at its top. Node and npm are needed here only,
# never at `cargo build`: the bundle is committed.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="$here/../../src/animate"
cd "$here"

# esbuild's binary comes from its optional platform package; its install
# script only checks it, so none is run.
npm ci --no-audit --no-fund --ignore-scripts

version_of() { node -p "JSON.parse(require('fs').readFileSync('node_modules/$1/package.json')).version"; }
version="$(version_of three)"
esbuild_version="$(version_of esbuild)"
header="$(head -n 5 node_modules/three/build/three.core.js)"
case "$header" in
*@license*) ;;
*) echo "three.core.js no longer starts with its @license header" >&2; exit 1 ;;
esac

body="$(mktemp)"
trap 'rm -f "$body"' EXIT
npx --no-install esbuild entry.js --bundle --minify --format=iife \
    --target=es2020 --legal-comments=none --charset=utf8 --log-level=warning \
    --outfile="$body"

{
    printf '%s\n' "$header"
    printf '/* three %s with OrbitControls (MIT, see THREE_LICENSE), bundled by tools/three/bundle.sh with esbuild %s */\n' \
        "$version" "$esbuild_version"
    cat "$body"
} > "$out/three.min.js"
cp node_modules/three/LICENSE "$out/THREE_LICENSE"

if grep -qi '</script' "$out/three.min.js"; then
    echo "the bundle contains </script, which would end its inline <script>" >&2
    exit 1
fi
echo "wrote $out/three.min.js ($(wc -c < "$out/three.min.js") bytes), three $version"
