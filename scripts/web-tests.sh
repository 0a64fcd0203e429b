#!/usr/bin/env bash
# The browser tests of issue 60 (docs/WEB.md), the last step of the README's test command:
# builds the wasm package and the page (scripts/build-web.sh), installs Debian's Chromium and
# Node.js when missing (scripts/ensure-vulkan.sh --for-web), installs the pinned test driver
# (web/tests/package-lock.json: playwright-core, which downloads no browser), serves the page on
# 127.0.0.1 and drives headless Chromium's WebGPU (SwiftShader, on the CPU) through it. The AO the
# page reads back is compared with `obscura render` of the same views (release build, lavapipe).
# Results, the EXRs and the page's screenshot land in target/web-test/.
set -euo pipefail
cd "$(dirname "$0")/.."
started=$SECONDS
bash scripts/ensure-vulkan.sh --for-web
bash scripts/build-web.sh target/web/site
# The CLI the page is compared with (`cargo test --workspace` built it already: nothing to do
# then). `--workspace`, not `-p obscura-cli`: features resolve over the whole workspace as the test
# command resolves them, so the test build is reused instead of compiled again.
cargo build -q --release --workspace --bins
# Installed again only when the lock file changed since the last install.
if ! cmp -s web/tests/package-lock.json web/tests/node_modules/.installed-lock.json 2>/dev/null; then
  (cd web/tests && npm ci --no-audit --no-fund --loglevel=error &&
    cp package-lock.json node_modules/.installed-lock.json)
fi
out=target/web-test
rm -rf "$out"
mkdir -p "$out"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
node web/tests/browser-tests.mjs --site target/web/site --cli target/release/obscura \
  --corpus crates/obscura-cli/tests/corpus --out "$out"
echo "web-tests: passed in $((SECONDS - started)) s; screenshot $out/page.png" >&2
