#!/usr/bin/env bash
# Renders docs/gallery/: close, mid, far and pond views of each weather over the built-in
# demo, the sky's shots and the coastal scene's, headless (the last of 45 frames of 1/15 s each, so the weather has set in
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
weathers=(light-snow blizzard drizzle downpour sleet sandstorm valley-fog fair-cumulus thunderstorm hail)
# The sky from the lawn and from the air: name, preset, extra options, eye, look-at.
sky_shots=(
  "fair-cumulus-up fair-cumulus - 5,1.7,25 0,60,-80"
  "fair-cumulus-below fair-cumulus --cloud-cover=0.95 0,900,0 100,950,-1000"
  "fair-cumulus-inside fair-cumulus --cloud-cover=0.95 0,1300,0 100,1250,-1000"
  "fair-cumulus-above fair-cumulus - 0,4500,3000 0,0,-6000"
  "layered-sky-up layered-sky - 5,1.7,25 0,60,-80"
  "layered-sky-above layered-sky - 0,4500,3000 0,0,-6000"
  "showers-around showers-around - 5,30,25 0,150,-2000"
  "nimbostratus-snow light-snow --cloud-type=nimbostratus 5,1.7,25 0,60,-80"
  "valley-fog-above valley-fog - 0,300,400 0,0,-300"
  "cumulus-shadows fair-cumulus - 0,1500,1500 0,0,-1500"
)
# The coastal scene (precip --coast): name, preset, eye, look-at.
coast_shots=(
  "calm-beach calm-sea -4,2.8,-18 -150,1.5,6"
  "calm-above calm-sea 60,40,-20 -400,0,20"
  "gale-beach gale -4,2.8,-18 -150,1.5,6"
  "gale-above gale 60,40,-20 -400,0,20"
  "gale-pier gale -68,3.6,-43 -40,1,70"
)
# Only some of them: tools/gallery.sh blizzard valley-fog (sky: tools/gallery.sh sky,
# the coast: tools/gallery.sh coast)
if [ "$#" -gt 0 ]; then weathers=("$@"); fi
if [ "${weathers[*]}" = "coast" ] || [ "$#" -eq 0 ]; then
  for shot in "${coast_shots[@]}"; do
    read -r name preset eye at <<<"$shot"
    "$precip" --coast --preset "presets/$preset.toml" --camera "$eye" --look-at "$at" \
      --size 640x360 --frames 45 --dt 0.0667 --out "$work/coast-$name" >/dev/null 2>&1
    cp "$work/coast-$name/frame_0044.png" "$out/coast-$name.png"
    echo "$out/coast-$name.png"
  done
  [ "${weathers[*]}" = "coast" ] && exit 0
fi
if [ "${weathers[*]}" = "sky" ] || [ "$#" -eq 0 ]; then
  for shot in "${sky_shots[@]}"; do
    read -r name preset extra eye at <<<"$shot"
    args=()
    [ "$extra" = "-" ] || args+=("$extra")
    "$precip" --preset "presets/$preset.toml" "${args[@]}" --camera "$eye" --look-at "$at" \
      --size 640x360 --frames 45 --dt 0.0667 --out "$work/sky-$name" >/dev/null 2>&1
    cp "$work/sky-$name/frame_0044.png" "$out/sky-$name.png"
    echo "$out/sky-$name.png"
  done
  [ "${weathers[*]}" = "sky" ] && exit 0
fi
for weather in "${weathers[@]}"; do
  for view in "${views[@]}"; do
    read -r name eye at <<<"$view"
    "$precip" --preset "presets/$weather.toml" --camera "$eye" --look-at "$at" \
      --size 640x360 --frames 45 --dt 0.0667 --out "$work/$weather-$name" >/dev/null 2>&1
    cp "$work/$weather-$name/frame_0044.png" "$out/$weather-$name.png"
    echo "$out/$weather-$name.png"
  done
done
