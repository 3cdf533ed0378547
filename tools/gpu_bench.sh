#!/usr/bin/env bash
# Packs what the GPU profile needs for the GPU machine (an H100 or H200, lent now and then) into
# `gpu_pack/` (ignored, under 64 MiB with the working tree): the release binary and
# `examples/ui_bench`, stripped and gzipped, and the Vulkan loader's and GL vendor library's
# Debian packages (NVIDIA's Vulkan driver loads libGLX_nvidia, which needs libglvnd: with the
# loader alone no adapter was found, 2026-11-30). `assets/`, `projects/` and `tools/gpu_run.sh`
# travel with the working tree. Then prints the one command to run there: `tools/gpu_run.sh`
# writes the profiles to `$OUT`, to be copied into docs/ and committed with the card named. Each
# profile stops starting new rows after its budget so that the whole fits one run.
set -euo pipefail
cd "$(dirname "$0")/.."

cargo build --release
cargo build --release --example ui_bench
rm -rf gpu_pack
mkdir -p gpu_pack/debs
cp target/release/bouncelab target/release/examples/ui_bench gpu_pack/
strip gpu_pack/bouncelab gpu_pack/ui_bench 2>/dev/null || true
gzip -9 gpu_pack/bouncelab gpu_pack/ui_bench
git rev-parse HEAD > gpu_pack/COMMIT
lists="$(mktemp -d)"
mkdir -p "$lists/partial"
opts=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 "-oDir::State::Lists=$lists")
apt-get "${opts[@]}" update -qq
(cd gpu_pack/debs && apt-get "${opts[@]}" download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 >/dev/null)
size=$(du -sm gpu_pack | cut -f1)
tree=$(( $(git ls-files -z | du -cb --files0-from=- | tail -1 | cut -f1) / 1048576 + 1 ))
if [ $((size + tree)) -ge 64 ]; then
  echo "gpu_pack is $size MiB and the working tree $tree MiB: the device tool carries at most 64 MiB" >&2
  exit 1
fi
echo "gpu_pack: ${size} MiB, the working tree ${tree} MiB (64 MiB in all travel)."
echo 'On the GPU machine: run with carry ["gpu_pack"], timeout_s 420: bash tools/gpu_run.sh'
