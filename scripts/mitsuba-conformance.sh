#!/usr/bin/env bash
# Renders every scene of Mitsuba's test set at its reference's spp and compares it with the reference;
# prints the table BENCHMARKS.md records ("Agreement with Mitsuba's references"). Usage:
#   scripts/mitsuba-conformance.sh [CAUSTIC_BINARY] [SHARED_DIR]   (ONLY=name,name to select scenes)
# Defaults: target/release/caustic and ../shared. Needs python3 to read refs.json.
set -u
caustic=$(realpath "${1:-target/release/caustic}")
shared=$(realpath "${2:-../shared}")
backend=${BACKEND:-gpu}
work=$(mktemp -d)
printf "%-30s %6s %8s %8s %9s %8s %7s\n" scene spp seconds mitsuba RMSE pass lum_z
python3 -c "
import json,sys
j=json.load(open('$shared/refs/mitsuba/refs.json'))
for n,v in j['scenes'].items(): print(n, v['file'], v['spp'], v['seconds'])
" | while read -r name file spp msec; do
  if [ -n "${ONLY:-}" ] && [[ ",$ONLY," != *",$name,"* ]]; then continue; fi
  log=$work/$name.log
  "$caustic" render "$shared/scenes/mitsuba/$file" --backend "$backend" -q -D spp="$spp" --spp "$spp" --variance -o "$work/$name.exr" > "$log" 2>&1
  secs=$(grep -o '| [0-9.]* s |' "$log" | tr -d '| s')
  cmp=$("$caustic" compare "$work/$name.exr" "$shared/refs/mitsuba/$name.exr" --image-spp "$spp" --reference-spp "$spp" 2>&1)
  rmse=$(echo "$cmp" | awk '/^RMSE/{print $2}')
  pass=$(echo "$cmp" | awk '/pass fraction/{print $4}')
  z=$(echo "$cmp" | awk '/luminance z/{print $4}')
  printf "%-30s %6s %8s %8s %9s %8s %7s\n" "$name" "$spp" "${secs:-ERR}" "$msec" "${rmse:-?}" "${pass:-?}" "${z:-?}"
  [ -z "$secs" ] && tail -3 "$log"
done
rm -rf "$work"
