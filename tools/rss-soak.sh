#!/usr/bin/env bash
# Resident memory of a long headless run of the viewer, per frame.
#
#   tools/rss-soak.sh VIEWER FRAMES OUT_DIR [viewer options...]
#
# Starts VIEWER (e.g. target/release/precip) headless for FRAMES frames writing PNGs
# into OUT_DIR, samples its VmRSS ten times a second, and prints the growth in KiB per
# frame between the samples taken once a fifth and 95 % of the frames are written
# (start-up and shut-down left out). A flat run prints about 0.
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 VIEWER FRAMES OUT_DIR [viewer options...]" >&2
  exit 2
fi
viewer=$1 frames=$2 out=$3
shift 3
rm -rf "$out"
env -u DISPLAY "$viewer" --frames "$frames" --out "$out" "$@" >/dev/null 2>&1 &
pid=$!
first_frame=$((frames / 5))
last_frame=$((frames * 95 / 100))
start_kib="" start_at=0 end_kib="" end_at=0
while kill -0 "$pid" 2>/dev/null; do
  # The folder appears with the first frame: count nothing until then.
  written=$({ find "$out" -name '*.png' 2>/dev/null || true; } | wc -l)
  kib=$(awk '$1 == "VmRSS:" { print $2 }' "/proc/$pid/status" 2>/dev/null || true)
  if [ -n "$kib" ]; then
    if [ -z "$start_kib" ] && [ "$written" -ge "$first_frame" ]; then
      start_kib=$kib start_at=$written
    fi
    if [ -z "$end_kib" ] && [ "$written" -ge "$last_frame" ]; then
      end_kib=$kib end_at=$written
    fi
  fi
  sleep 0.1
done
status=0
wait "$pid" || status=$?
if [ -z "$start_kib" ] || [ -z "$end_kib" ] || [ "$end_at" -le "$start_at" ]; then
  echo "rss-soak: too few samples (the viewer exited with $status)" >&2
  exit 1
fi
awk -v a="$start_kib" -v b="$end_kib" -v n=$((end_at - start_at)) 'BEGIN { printf "%.1f\n", (b - a) / n }'
