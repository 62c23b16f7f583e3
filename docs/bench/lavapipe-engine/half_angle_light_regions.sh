#!/usr/bin/env bash
# Half-angle frame GPU time (the profiler's `half_angle` scope, ms) with the
# light buffer updated in the slices' regions (the default) against every
# texel every slice (`LightRegions::Whole`), 3 alternating rounds, from the
# repository root. /tmp/sl_whole and /tmp/sl_slices: the same tree built twice,
# `render_with`/`record_with` called with Whole, then with Slices.
# Each round also writes /tmp/ha_{whole,slices}_SCENE.png: compare with cmp.
for round in 1 2 3; do
 for b in whole slices; do
  for spec in "slab-under-sphere 256" "nucleon 256" "phantom 128" "noise 128"; do
   set -- $spec
   ms=$(/tmp/sl_$b render --technique half-angle --scene tests/scenes/$1.toml --size $2x$2 --out /tmp/ha_${b}_$1.png 2>&1 | awk '$1=="half_angle"{print $3}')
   echo "$round $b $1 $2 $ms"
  done
 done
done
