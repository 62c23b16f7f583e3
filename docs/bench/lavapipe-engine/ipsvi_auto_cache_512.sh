#!/usr/bin/env bash
# Alternating rounds: the engine at 512x512, IPSVI default (cache auto) against cache_size=256.
# Usage: docs/bench/lavapipe-engine/ipsvi_auto_cache_512.sh BIN [ROUNDS], from the repository root.
# GPU frame time (the profile's total) and the line dispatches' sum, per round, each configuration once.
bin=$1; rounds=${2:-3}
for r in $(seq 1 $rounds); do
  for c in auto 256; do
    set_args=(); [ "$c" = 256 ] && set_args=(--set ipsvi.cache_size=256)
    out=$("$bin" render --scene tests/scenes/engine.toml --technique ipsvi --size 512x512 "${set_args[@]}" --out "${TMPDIR:-/tmp}/ipsvi_auto_cache_$c.png" 2>&1)
    line=$(echo "$out" | awk '$1=="ipsvi_line"{s+=$3} END{print s}')
    total=$(echo "$out" | grep -E "^total " | awk '{print $2}')
    note=$(echo "$out" | grep -o "cache [0-9]*[^;]*px" | head -1)
    echo "round $r cache=$c line_ms=$line total_ms=$total [$note]"
  done
done
