#!/usr/bin/env bash
# The AO radius cap (max_radius_px, seed 002 §3.5) on the device, in one call:
# 1. every estimator's single-pass row and ray-sd-vao against the build before the cap (whose
#    radius was one uniform): what the per-pixel radius costs when no cap is set
#    ($OUT/estimators.md);
# 2. the new build alone on a Sponza close-up (a wall within a metre of the camera), without a
#    cap (the old column) and with the authors' 512 px (the new column) ($OUT/cap-512.md).
# ROUNDS, OLD_BIN as in scripts/device-bench-old-new.sh.
here=$(dirname "$0")
TECHNIQUES=vao,hbao,hbao+,gtao,gtao-vb,ssao,sao,pyramid-hbao,ray-sd-vao NAME=estimators \
  bash "$here/device-bench-old-new.sh"
TECHNIQUES=vao,hbao+,gtao-vb,ray-sd-vao NAME=cap-512 OLD_BIN=.devbin/obscura \
  VIEW="--eye=-9.5,1.0,-3.6 --target=-9.5,1.0,-6 --fov 60" EXTRA_NEW="--max-radius-px 512" \
  bash "$here/device-bench-old-new.sh"
