#!/usr/bin/env bash
# The per-scene specialization table (BENCHMARKS.md, "Specialised against pruned"): for each scene,
# in one run, interleaved, the GPU throughput of the kernel with every path compiled in
# (CAUSTIC_SPECIALIZE=0), specialised to the scene's feature mask by the driver (spec constant 0,
# the default), and "pruned": the same SPIR-V with the mask frozen and every unused path deleted by
# spirv-opt's dead-code passes (a hand-pruned kernel without the hand), run through
# CAUSTIC_KERNEL_SPV.
#
#   scripts/specialization.sh prepare CAUSTIC SCENES_DIR WORK   # needs spirv-opt (Debian spirv-tools)
#   scripts/specialization.sh run CAUSTIC SCENES_DIR WORK       # on the GPU machine; prints the table
#
# SCENES_DIR holds SCENES.txt (paths relative to it, as ../shared/scenes/mitsuba does). `prepare`
# reads each scene's mask from `caustic bench` and writes WORK/masks.txt and WORK/k<mask>.spv; the
# kernel is the one embedded in CAUSTIC, so both steps must use the same build.
set -euo pipefail
step=$1 caustic=$(realpath "$2") scenes=$(realpath "$3") work=$4
kernel=$(cd "$(dirname "$0")/.." && pwd)/host/shaders/caustic-kernel.spv
mkdir -p "$work"
args() { # the scene's arguments: cbox at 512² and depth 8 as elsewhere in BENCHMARKS
  local p="$scenes/$1"
  case $(basename "$1" .xml) in
    cbox) echo "$p -D res=512 -D max_depth=8" ;;
    sensor_thinlens) echo "$p -D spp=256" ;;
    *) echo "$p" ;;
  esac
}
throughput() { "$@" --backend gpu 2>&1 | awk -F'|' '/^\| gpu/ {print $6+0}'; }
case $step in
  prepare)
    : > "$work/masks.txt"
    while read -r rel; do
      # shellcheck disable=SC2046
      mask=$("$caustic" bench $(args "$rel") -D res=16 --backend cpu --spp 1 2>&1 | awk '/^kernel paths/ {print $3}')
      echo "$rel $mask" >> "$work/masks.txt"
      [ -f "$work/k$mask.spv" ] || spirv-opt --set-spec-const-default-value "0:$mask" --freeze-spec-const \
        --fold-spec-const-op-composite --ccp --eliminate-dead-branches --eliminate-dead-code-aggressive \
        --eliminate-dead-functions --merge-blocks "$kernel" -o "$work/k$mask.spv"
    done < "$scenes/SCENES.txt"
    ;;
  run)
    echo "| scene | every path | specialised | pruned | specialised / every | pruned / specialised |"
    echo "|---|---|---|---|---|---|"
    while read -r rel mask; do
      spp=256; [ "$(basename "$rel" .xml)" = bsdf_dielectric_diamond ] && spp=64
      # shellcheck disable=SC2046
      {
        full=$(CAUSTIC_SPECIALIZE=0 throughput "$caustic" bench $(args "$rel") --spp $spp)
        spec=$(throughput "$caustic" bench $(args "$rel") --spp $spp)
        pruned=$(CAUSTIC_KERNEL_SPV="$work/k$mask.spv" throughput "$caustic" bench $(args "$rel") --spp $spp)
      }
      awk -v s="$(basename "$rel" .xml)" -v a="$full" -v b="$spec" -v c="$pruned" \
        'BEGIN { printf "| %s | %.2f | %.2f | %.2f | %.2f× | %.3f× |\n", s, a, b, c, b / a, c / b }'
    done < "$work/masks.txt"
    ;;
  *) echo "usage: $0 prepare|run CAUSTIC SCENES_DIR WORK" >&2; exit 2 ;;
esac
