#!/usr/bin/env bash
# Packs what tools/gpu-report.sh needs on a machine with a GPU and no Rust
# toolchain, into folders that .git/info/exclude ignores and the device tool
# carries (`carry: [".gl", ".dev"]`):
#   .gl/   the Vulkan loader and GL dispatch libraries, the Khronos validation
#          layer and a TrueType font for the report's plot, as Debian packages
#          (unpacked there with `dpkg -x`);
#   .dev/pack.tar.xz   bin/ (precip, report and the conformance suites' test
#          binaries, stripped) — 13 MB where the binaries are 76 MB.
# Then, on the device (one call, about 2.5 minutes on an H100):
#   for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; mkdir -p /tmp/p &&
#   tar xJf .dev/pack.tar.xz -C /tmp/p; bash tools/gpu-report.sh /tmp/p/bin $OUT
set -eu -o pipefail
cd "$(git rev-parse --show-toplevel)"
exclude=$(git rev-parse --git-path info/exclude)
mkdir -p "$(dirname "$exclude")"
grep -qx '/.gl/' "$exclude" 2>/dev/null || echo '/.gl/' >> "$exclude"
grep -qx '/.dev/' "$exclude" 2>/dev/null || echo '/.dev/' >> "$exclude"
cargo build --release -p precip-viewer -p precip-benches
# The conformance suites' binaries, by the name of their test file, as cargo
# reports them (other crates build tests of the same names).
suites=$(cargo test --release -p precip-conformance --no-run --message-format=json |
  python3 -c '
import json, sys
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m.get("executable") \
            and m["target"]["kind"] == ["test"] and "precip-conformance" in m["package_id"]:
        print(m["target"]["name"], m["executable"])
')
rm -rf .gl .dev && mkdir -p .gl .dev /tmp/amd64/partial
o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
# shellcheck disable=SC2086
apt-get $o update >/dev/null
# shellcheck disable=SC2086
(cd .gl && apt-get $o download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 \
  libgles2 vulkan-validationlayers fonts-dejavu-core)
pack=$(mktemp -d)
mkdir -p "$pack/bin"
cp target/release/precip target/release/report "$pack/bin/"
while read -r suite executable; do
  cp "$executable" "$pack/bin/$suite"
done <<< "$suites"
strip "$pack"/bin/*
tar cJf .dev/pack.tar.xz -C "$pack" bin
rm -rf "$pack"
du -sh .gl .dev
