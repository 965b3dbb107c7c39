#!/usr/bin/env bash
# The GPU numbers of the README and docs/performance.md, on a machine with a GPU:
#
#   bash tools/gpu-report.sh BIN OUT
#
# BIN holds `precip` and `report` (target/release, or copies) and, when present, the
# conformance suites' test binaries under their test names (contract, terrain, …;
# `cargo test --release -p precip-conformance --no-run` builds them). OUT receives
#   gpu.txt          the report's output, the viewer's summary lines, the suites'
#                    results, in order;
#   report.json/png  the report with its full frames at 1920×1080 (10⁴ to 10⁷
#                    particles; no window runs: the peer needs a display);
#   frames.tar       the last frame of each viewer run, as PNG.
# The viewer runs the demo for 120 frames on both backends with its defaults, the
# blizzard and the downpour, at 1280×720 and 1920×1080, headless; its summary (mean
# frame time, GPU ms per pass, each feature's share) is kept. The conformance suites
# run last, with PRECIP_REQUIRE_GPU=1 and the vk backend under the validation layer
# (installed by unpacking .gl's vulkan-validationlayers package: tools/gpu-pack.sh
# packs it all and gives the device's command).
set -u -o pipefail
BIN=${1:?BIN: the folder of precip and report}
OUT=${2:?OUT: the folder for the results}
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
LOG=$OUT/gpu.txt
: > "$LOG"
say() { echo "== $*" | tee -a "$LOG"; }

say "$(date -u +%FT%TZ) $(nvidia-smi -L 2>/dev/null || echo 'no nvidia-smi')"
say "report --size 1920x1080 --no-peer"
timeout 300 "$BIN/report" "$OUT/report.json" --size 1920x1080 --no-peer 2>&1 | tee -a "$LOG"

FRAMES=$(mktemp -d)
for size in 1280x720 1920x1080; do
  for backend in wgpu vk; do
    for preset in default blizzard downpour; do
      name=$backend-$preset-$size
      args=(--backend "$backend" --size "$size" --frames 120 --out "$FRAMES/$name")
      [ "$preset" != default ] && args+=(--preset "$preset")
      say "precip ${args[*]}"
      timeout 120 "$BIN/precip" "${args[@]}" 2>&1 | grep -E "frames in|GPU ms|error|warning" | tee -a "$LOG"
      last=$(ls "$FRAMES/$name"/frame_*.png 2>/dev/null | sort -V | tail -1)
      [ -n "$last" ] && cp "$last" "$FRAMES/$name.png"
      rm -rf "${FRAMES:?}/$name"
    done
  done
done
tar cf "$OUT/frames.tar" -C "$FRAMES" .
rm -rf "${FRAMES:?}"

for suite in contract terrain fast_camera sea shore sensors soak; do
  [ -x "$BIN/$suite" ] || continue
  say "conformance $suite (PRECIP_REQUIRE_GPU=1)"
  PRECIP_REQUIRE_GPU=1 timeout 240 "$BIN/$suite" 2>&1 |
    grep -E "^test |test result|SKIPPED|panicked|validation" | tee -a "$LOG"
done
say "$(date -u +%FT%TZ) done"
