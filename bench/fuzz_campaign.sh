#!/usr/bin/env bash
# Fuzzing campaign over every reader's libFuzzer target (tests/fuzz; AddressSanitizer and
# UndefinedBehaviorSanitizer built in): each target starts from its committed seeds
# (tests/fuzz/corpus/<reader>/) and runs RUNS inputs in a scratch corpus. Prints, per reader, the
# executions, their rate and the findings (crash-* / leak-* / timeout-* files, kept in OUT);
# exits 1 when any reader has a finding.
#   bench/fuzz_campaign.sh BUILD_DIR [RUNS] [OUT]     (make fuzz: build-fuzz, 20000 runs)
# READERS="k vtk" runs only those (several campaigns with disjoint READERS can share the cores).
set -u
BUILD=${1:?build directory with fuzz/fuzz_<reader>}
RUNS=${2:-1000000}
OUT=${3:-$(mktemp -d "${TMPDIR:-/tmp}/hexdom-fuzz.XXXXXX")}
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
SEEDS=$HERE/../tests/fuzz/corpus
found=0
printf '%-15s %10s %8s %9s %s\n' reader executions "exec/s" seconds findings
for target in "$BUILD"/fuzz/fuzz_*; do
  reader=${target##*/fuzz_}
  if [ -n "${READERS:-}" ] && [[ " $READERS " != *" $reader "* ]]; then continue; fi
  mkdir -p "$OUT/$reader/corpus" "$OUT/$reader/findings"
  start=$(date +%s.%N)
  HEXDOM_FUZZ_DIR=$OUT/$reader ASAN_OPTIONS=detect_leaks=1 "$target" -runs="$RUNS" -max_len=4096 -timeout=10 \
    -rss_limit_mb=2048 -artifact_prefix="$OUT/$reader/findings/" "$OUT/$reader/corpus" "$SEEDS/$reader" \
    > "$OUT/$reader/log" 2>&1
  rc=$?
  seconds=$(echo "$(date +%s.%N) - $start" | bc)
  execs=$(grep -o 'Done [0-9]* runs' "$OUT/$reader/log" | grep -o '[0-9]*')
  [ -z "$execs" ] && execs=$(grep -o '^#[0-9]*' "$OUT/$reader/log" | tail -1 | tr -d '#')
  n=$(ls "$OUT/$reader/findings" | wc -l)
  [ "$rc" -ne 0 ] || [ "$n" -ne 0 ] && found=1
  printf '%-15s %10s %8.0f %9.1f %s\n' "$reader" "${execs:-?}" "$(echo "${execs:-0} / $seconds" | bc -l)" "$seconds" \
    "$n$( [ "$rc" -ne 0 ] && echo " (exit $rc: $OUT/$reader/log)")"
done
echo "logs, corpora and findings: $OUT"
exit $found
