#!/usr/bin/env bash
# The stochastic depth maps' readers against the build before (issue 11's "SD AO pass ≤ 2× its
# regular twin"): every row that reads a map, on Sponza 1920x1080 + 64 (S = 4, N = 4), and the
# regular twins, in one device call (scripts/device-bench-old-new.sh; ROUNDS, OLD_BIN as there).
# Writes $OUT/summary.md and $OUT/summary-runs.tar.gz.
TECHNIQUES=ssao,sd-ssao,sd-ssao-stenciled,hbao,sd-hbao,hbao+,sd-hbao+,sd-hbao+-stenciled,gtao-vb,sd-gtao-vb,sd-gtao-vb-stenciled,vao,sd-vao,sd-svao,ray-sd-vao \
  NAME=summary exec bash "$(dirname "$0")/device-bench-old-new.sh"
