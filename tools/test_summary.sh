#!/usr/bin/env bash
# One line summed over cargo test's `test result:` lines of the log on stdin:
# `N passed, N failed, N ignored` (tools/test.sh ends with it; CI reads it).
awk '/^test result:/ {
       for (i = 1; i < NF; i++) {
         if ($(i + 1) ~ /^passed/) p += $i
         if ($(i + 1) ~ /^failed/) f += $i
         if ($(i + 1) ~ /^ignored/) g += $i
       }
     }
     END { printf "%d passed, %d failed, %d ignored\n", p, f, g }'
