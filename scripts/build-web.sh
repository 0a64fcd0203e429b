#!/usr/bin/env bash
# Build obscura's web page (issue 60, docs/WEB.md) into a folder any static host serves:
#   <out>/index.html, app.js, style.css     the page
#   <out>/pkg/                              the npm-ready package: obscura.js, obscura_bg.wasm,
#                                           obscura.d.ts, package.json
# Usage: build-web.sh [OUT]   (default target/web/site)
#
# Needs rustup's wasm32-unknown-unknown target (added here) and wasm-bindgen's CLI of exactly the
# version Cargo.lock pins for the `wasm-bindgen` crate: installed with cargo into target/web-tools
# on first use (crates.io has no prebuilt binary and npm no official one), reused after that.
# Installed unoptimised (--debug) and without its test runner's TLS stack (--no-default-features):
# 2.7 min of CPU instead of 6.4 on two cores, for 4 s instead of 1 s per run, with the same
# output byte for byte (compared on this page's module, 2026-12-07).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-target/web/site}"
version="$(grep -A1 '^name = "wasm-bindgen"$' Cargo.lock | sed -n 's/^version = "\(.*\)"$/\1/p')"
tools="$PWD/target/web-tools"
bindgen="$tools/bin/wasm-bindgen"
if ! { [ -x "$bindgen" ] && [ "$("$bindgen" --version)" = "wasm-bindgen $version" ]; }; then
  echo "build-web: installing wasm-bindgen-cli $version into $tools (once)" >&2
  cargo install -q wasm-bindgen-cli --version "$version" --root "$tools" --debug \
    --no-default-features
fi
if command -v rustup >/dev/null; then
  rustup target list --installed | grep -qx wasm32-unknown-unknown ||
    rustup target add wasm32-unknown-unknown
fi
# The `web` profile (Cargo.toml): optimised for size, in its own folder beside the native build.
cargo build -q --profile web --target wasm32-unknown-unknown -p obscura-web
rm -rf "$out"
mkdir -p "$out/pkg"
"$bindgen" --target web --out-dir "$out/pkg" --out-name obscura \
  target/wasm32-unknown-unknown/web/obscura_web.wasm
cat > "$out/pkg/package.json" <<JSON
{
  "name": "obscura-web",
  "version": "$(sed -n 's/^version = "\(.*\)"$/\1/p' Cargo.toml | head -1)",
  "description": "Screen-space ambient occlusion that keeps what the depth buffer hides, on WebGPU",
  "license": "MIT OR Apache-2.0",
  "type": "module",
  "main": "obscura.js",
  "types": "obscura.d.ts",
  "files": ["obscura.js", "obscura_bg.wasm", "obscura.d.ts", "obscura_bg.wasm.d.ts"],
  "sideEffects": ["./snippets/*"]
}
JSON
cp web/index.html web/app.js web/style.css "$out/"
wasm="$out/pkg/obscura_bg.wasm"
echo "build-web: $out ($(wc -c <"$wasm") bytes of wasm, $(gzip -9 -c "$wasm" "$out/pkg/obscura.js" | wc -c) gzipped with its JS)" >&2
