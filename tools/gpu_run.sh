#!/usr/bin/env bash
# Run on the GPU machine from the repository root, after `tools/gpu_bench.sh` packed `gpu_pack/`
# (the device tool's `run` with `carry: ["gpu_pack"]`, `bash tools/gpu_run.sh`, timeout_s 420).
# One device call: the 1080p profile of every mode and scene (the budget; rcs on four scenes, its
# rows converge a cache first), a 720p/4K scaling subset, and the editor's UI frames, with the
# SM clocks sampled once a second. Everything lands in $OUT (at most 8 files come back: three JSON
# profiles, the traces and the rest in two archives). P1, PR, P2: the three profiles' budgets (s).
set -u
for f in gpu_pack/debs/*.deb; do dpkg -x $f /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json BOUNCELAB_ADAPTER=nvidia BOUNCELAB_COMMIT=$(cat gpu_pack/COMMIT) XDG_RUNTIME_DIR=/tmp
gunzip -f gpu_pack/bouncelab.gz gpu_pack/ui_bench.gz; chmod +x gpu_pack/bouncelab gpu_pack/ui_bench
B=gpu_pack/bouncelab
{ nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv; nproc; } > $OUT/machine.txt 2>&1
nvidia-smi dmon -s pc -d 1 > $OUT/dmon.txt 2>&1 &
t0=$(date +%s)
$B profile --resolutions 1920x1080 --modes direct,ism,ism-ritschel,mrt,sshgi --budget-s ${P1:-170} --out $OUT/p1080.json --traces /tmp/tr1080 > $OUT/p1080.md 2> $OUT/log.txt
echo "1080p done in $(( $(date +%s) - t0 )) s" >> $OUT/log.txt
$B profile --resolutions 1920x1080 --modes rcs --scenes ${SR:-cornell,window,hall,skylight} --budget-s ${PR:-45} --out $OUT/prcs.json --traces /tmp/trr > $OUT/prcs.md 2>> $OUT/log.txt
echo "rcs done in $(( $(date +%s) - t0 )) s" >> $OUT/log.txt
$B profile --resolutions 1280x720,3840x2160 --modes direct,ism,sshgi,mrt --scenes ${S2:-rooms,window} --budget-s ${P2:-40} --out $OUT/pscale.json --traces /tmp/trs > $OUT/pscale.md 2>> $OUT/log.txt
echo "scale done in $(( $(date +%s) - t0 )) s" >> $OUT/log.txt
timeout 60 gpu_pack/ui_bench 3 direct,ism,mrt,sshgi,rcs > $OUT/ui.md 2>> $OUT/log.txt
echo "ui done in $(( $(date +%s) - t0 )) s" >> $OUT/log.txt
kill %1 2>/dev/null
(cd /tmp && tar czf $OUT/traces.tgz tr1080 trr trs)
(cd $OUT && tar czf rest.tgz machine.txt dmon.txt log.txt p1080.md prcs.md pscale.md ui.md && rm -f dmon.txt log.txt)
cat $OUT/machine.txt; rm -f $OUT/machine.txt; cat $OUT/ui.md; cut -d'|' -f2-11,14 $OUT/p1080.md | tail -62; cut -d'|' -f2-13 $OUT/prcs.md | tail -5
rm -f $OUT/*.md
