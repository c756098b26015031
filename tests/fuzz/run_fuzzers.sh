#!/bin/sh
# Runs each libFuzzer target for a bounded time and writes a summary (executions, crashes).
# Usage: run_fuzzers.sh BUILD_DIR OUT_DIR SECONDS [TARGET...]   (called by `make fuzz`)
# The seed corpus and crash reproducers in the repo are read-only inputs; what the fuzzers
# add goes to BUILD_DIR/fuzz_corpus/<target>, what crashes to OUT_DIR/fuzz/<target>/.
# Fork mode with -ignore_crashes: one crash does not end the run, so a run reports every
# distinct problem it reaches in its time (each artifact replays with fuzz_<target> FILE).
set -u
build=$1 out=$2 seconds=$3
shift 3
targets=${*:-scene quantity snapshot point_cloud}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out/fuzz"
summary=$out/fuzz_summary.txt
found=0
{
  echo "# mppm fuzzing: $(date -u '+%Y-%m-%d %H:%M UTC'), ${seconds} s per target, clang $(clang++ --version | sed -n '1s/.*version \([0-9.]*\).*/\1/p'), ASan+UBSan"
  printf '%-12s %12s %8s %8s %8s %8s\n' target executions exec/s corpus crashes timeouts
} > "$summary"
for t in $targets; do
  work=$build/fuzz_corpus/$t
  artifacts=$out/fuzz/$t
  log=$out/fuzz/$t.log
  rm -rf "$artifacts" && mkdir -p "$work" "$artifacts"
  # A private TMPDIR, in memory when possible: the snapshot and points targets go through
  # files, and an accepted input is rewritten (with fsync) to check the round trip.
  tmp=$(mktemp -d -p /dev/shm 2>/dev/null || mktemp -d) || exit 1
  dict=""
  [ -f "$here/$t.dict" ] && dict="-dict=$here/$t.dict"
  echo "fuzz_$t: ${seconds} s (log: $log)"
  TMPDIR=$tmp LSAN_OPTIONS="suppressions=$here/lsan_suppressions.txt" \
    "$build/bin/fuzz_$t" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -artifact_prefix="$artifacts/" $dict \
      "$work" "$here/corpus/$t" "$here/crashes/$t" > "$log" 2>&1
  rm -rf "$tmp"
  # The parent's progress lines: "#RUNS: cov: .. corp: N exec/s: R oom/timeout/crash: a/b/c time: ..".
  last=$(grep -E '^#[0-9]+: cov:' "$log" | tail -1)
  runs=$(echo "$last" | sed -n 's/^#\([0-9]*\):.*/\1/p')
  rate=""
  [ -n "$runs" ] && rate=$((runs / seconds))  # average over the run (the last line is momentary)
  corpus=$(ls "$work" | wc -l)
  crashes=$(ls "$artifacts" | grep -c -E '^(crash|leak|oom)-' || true)
  timeouts=$(ls "$artifacts" | grep -c -E '^(timeout|slow-unit)-' || true)
  printf '%-12s %12s %8s %8s %8s %8s\n' "$t" "${runs:-?}" "${rate:-?}" "$corpus" "$crashes" "$timeouts" >> "$summary"
  [ "$crashes" -gt 0 ] || [ "$timeouts" -gt 0 ] && found=1
done
echo "# executions: inputs run without a crash, hang or leak except the artifacts counted" >> "$summary"
cat "$summary"
if [ $found -ne 0 ]; then
  echo "problems found: reproducers in $out/fuzz/<target>/ (replay: $build/bin/fuzz_<target> FILE)" >&2
  exit 1
fi
