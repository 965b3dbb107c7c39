#!/usr/bin/env bash
# Renders docs/gallery/: close, mid, far and pond views of each weather over the built-in
# demo, headless (the last of 45 frames of 1/15 s each, so the weather has set in
# and the cover has started to build at the default time scale). Run from the
# repository root after `cargo build --release`; about 4 minutes on lavapipe (name
# presets as arguments to render only those).
set -euo pipefail
cd "$(dirname "$0")/.."
precip=target/release/precip
out=docs/gallery
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
views=(
  "close 5,1.7,25 0,1,0"
  "mid 22,6,38 0,1,0"
  "far 70,35,95 0,0,0"
  "pond -17,0.5,21 0,2.5,0"
)
weathers=(light-snow blizzard drizzle downpour sleet sandstorm valley-fog fair-cumulus thunderstorm)
# Only some of them: tools/gallery.sh blizzard valley-fog
if [ "$#" -gt 0 ]; then weathers=("$@"); fi
for weather in "${weathers[@]}"; do
  for view in "${views[@]}"; do
    read -r name eye at <<<"$view"
    "$precip" --preset "presets/$weather.toml" --camera "$eye" --look-at "$at" \
      --size 640x360 --frames 45 --dt 0.0667 --out "$work/$weather-$name" >/dev/null 2>&1
    cp "$work/$weather-$name/frame_0044.png" "$out/$weather-$name.png"
    echo "$out/$weather-$name.png"
  done
done
