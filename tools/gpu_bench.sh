#!/usr/bin/env bash
# Packs what the GPU profile needs for the GPU machine (an H100 or H200, lent now and then) into
# `gpu_pack/` (ignored, under 64 MiB): the release binary and the Vulkan loader's Debian
# packages; `assets/` and `projects/` travel with the working tree. Then prints the one command
# to run there (the device tool's `run`, with `carry: ["gpu_pack"]`): it writes
# `$OUT/gpu-profile.json`, `$OUT/gpu-profile.md` and `$OUT/gpu-trace/<mode>.json`, to be copied
# into docs/ and committed with the card named. The whole profile stops starting new rows after
# `--budget-s` (default 270 s) so that it fits one run.
set -euo pipefail
cd "$(dirname "$0")/.."

cargo build --release
rm -rf gpu_pack
mkdir -p gpu_pack/debs
cp target/release/bouncelab gpu_pack/
strip gpu_pack/bouncelab 2>/dev/null || true
git rev-parse HEAD > gpu_pack/COMMIT
lists="$(mktemp -d)"
mkdir -p "$lists/partial"
opts=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 "-oDir::State::Lists=$lists")
apt-get "${opts[@]}" update -qq
(cd gpu_pack/debs && apt-get "${opts[@]}" download libvulkan1 >/dev/null)
size=$(du -sm gpu_pack | cut -f1)
if [ "$size" -ge 64 ]; then
  echo "gpu_pack is $size MiB: the device tool carries at most 64 MiB" >&2
  exit 1
fi
cat <<CMD
gpu_pack: ${size} MiB. On the GPU machine (carry: ["gpu_pack"], timeout_s 400):

for f in gpu_pack/debs/*.deb; do dpkg -x \$f /; done; ldconfig; export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json BOUNCELAB_ADAPTER=nvidia BOUNCELAB_COMMIT=\$(cat gpu_pack/COMMIT); gpu_pack/bouncelab profile --out \$OUT/gpu-profile.json --traces \$OUT/gpu-trace --budget-s 270 > \$OUT/gpu-profile.md; tail -40 \$OUT/gpu-profile.md
CMD
