#!/usr/bin/env bash
# Packs what tools/gpu-report.sh needs on a machine with a GPU and no Rust
# toolchain, into folders that .git/info/exclude ignores and the device tool
# carries (`carry: [".gl", ".dev"]`):
#   .gl/   the Vulkan loader and GL dispatch libraries, and the Khronos validation
#          layer, as Debian packages (unpacked there with `dpkg -x`);
#   .dev/pack.tar.xz   bin/ (precip, report and the conformance suites' test
#          binaries, stripped) — 18 MB where the binaries are 76 MB.
# Then, on the device (one call, about 2.5 minutes on an H100):
#   for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; mkdir -p /tmp/p &&
#   tar xJf .dev/pack.tar.xz -C /tmp/p; bash tools/gpu-report.sh /tmp/p/bin $OUT
set -eu -o pipefail
cd "$(git rev-parse --show-toplevel)"
grep -qx '/.gl/' .git/info/exclude 2>/dev/null || echo '/.gl/' >> .git/info/exclude
grep -qx '/.dev/' .git/info/exclude 2>/dev/null || echo '/.dev/' >> .git/info/exclude
cargo build --release -p precip-viewer -p precip-benches
cargo test --release -p precip-conformance --no-run
rm -rf .gl .dev && mkdir -p .gl .dev /tmp/amd64/partial
o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
# shellcheck disable=SC2086
apt-get $o update >/dev/null
# shellcheck disable=SC2086
(cd .gl && apt-get $o download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 \
  libgles2 vulkan-validationlayers)
pack=$(mktemp -d)
mkdir -p "$pack/bin"
cp target/release/precip target/release/report "$pack/bin/"
for suite in contract terrain fast_camera sea shore sensors soak; do
  newest=$(ls -t target/release/deps/"$suite"-* | grep -v '\.d$' | head -1)
  cp "$newest" "$pack/bin/$suite"
done
strip "$pack"/bin/*
tar cJf .dev/pack.tar.xz -C "$pack" bin
rm -rf "$pack"
du -sh .gl .dev
