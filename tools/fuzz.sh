#!/usr/bin/env bash
# Coverage-guided fuzzing (cargo-fuzz, libFuzzer, AddressSanitizer) of the readers a user feeds
# files to: project files, glTF/GLB, and the images `bouncelab compare` reads. Each target
# starts from the committed seeds (fuzz/seeds/<target>) plus what earlier runs found
# (fuzz/corpus/<target>, ignored by git) and runs RUNS executions (default 1,000,000).
# A crash leaves its input under fuzz/artifacts/<target>/; make it a regression test.
#
#   tools/fuzz.sh                      # all three targets, a million executions each
#   RUNS=20000 tools/fuzz.sh gltf_import
#
# Needs the nightly toolchain and cargo-fuzz (`cargo install cargo-fuzz`). Not part of CI:
# the instrumented build alone takes longer than the whole test suite on two cores.
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
runs="${RUNS:-1000000}"
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(project_file gltf_import image_read)
for t in "${targets[@]}"; do
  mkdir -p "corpus/$t"
  echo "== $t: $runs executions"
  cargo +nightly fuzz run --fuzz-dir . "$t" "corpus/$t" "seeds/$t" -- \
    -runs="$runs" -rss_limit_mb=4096 -max_len=65536 -timeout=10 -print_final_stats=1
done
