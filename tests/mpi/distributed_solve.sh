#!/bin/sh
# mppm-solve under mpirun (tests/mpi.cmake): usage
#   distributed_solve.sh MODE MPIEXEC BIN_DIR SCENE WORK_DIR [PROCESSES... | EXPECTED ARGS...]
# MODE same:      the run directory at each process count (1 and 2 threads each) holds the files of
#                 the one-process run byte for byte (all but log.txt and run_info.json, which give
#                 wall times; run_info.json must say how many processes ran)
# MODE checkpoint: a checkpoint written by N processes is the one-process file, and continues on M
#                 (see below)
# MODE nan:       a NaN written into the last point of the file, which the partition gives to the
#                 last of 3 processes: exit 3, one message naming that point and its process
# MODE refused:   a run the distributed run refuses (SCENE, then EXPECTED and mppm-solve's options
#                 after WORK_DIR): exit 2, one message holding EXPECTED, no run directory
# MODE taken:     -o names an existing directory: the first process refuses it, exit 2, one message
# MODE interrupt: SIGTERM to mpirun during the run: every process stops at the same step, exit 1,
#                 one message, status "interrupted" and a last snapshot
set -u
mode=$1 mpiexec=$2 bin=$3 scene=$4 work=$5
shift 5
fail() { echo "FAIL: $*"; exit 1; }
run_mpi() {  # run_mpi PROCESSES THREADS ARGS...: mppm-solve under mpirun, its stderr in $work/err.txt
  p=$1 t=$2
  shift 2
  OMP_NUM_THREADS=$t "$mpiexec" --oversubscribe --bind-to none -np "$p" "$bin/mppm-solve" "$@" --quiet 2> "$work/err.txt"
}
# The lines mppm-solve printed (mpirun adds its own banner about the exit code).
mppm_lines() { grep -c '^mppm-solve' "$work/err.txt"; }

rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"
"$bin/mppm-preprocess" "$scene" -o "$work/points.vtp" > /dev/null || fail "mppm-preprocess $scene"

case $mode in
same)
  "$bin/mppm-solve" "$scene" --points "$work/points.vtp" -o "$work/one" --quiet || fail "the one-process run"
  files=$(cd "$work/one" && find . -type f ! -name log.txt ! -name run_info.json | sort)
  if grep -q '^effects:.*viscoplasticity' "$scene"; then
    # The comparison must cover plastic flow: the last row's plastic dissipation (column 6) is > 0.
    tail -1 "$work/one/energy.csv" | awk -F, '{ exit !($6 > 0) }' || fail "no plastic dissipation in the run"
  fi
  if grep -q '^effects:.*damage' "$scene"; then
    # And breakage: bonds broke and points detached (the summary line of log.txt).
    grep -q '^completed .* broken bonds [1-9][0-9]* (pairs).* detached points [1-9]' "$work/one/log.txt" ||
      fail "no bond broke or no point detached in the run"
  fi
  for p in "$@"; do
    for t in 1 2; do
      out="$work/np$p.threads$t"
      run_mpi "$p" "$t" "$scene" --points "$work/points.vtp" -o "$out" || { cat "$work/err.txt"; fail "np $p threads $t"; }
      test "$(cd "$out" && find . -type f ! -name log.txt ! -name run_info.json | sort)" = "$files" ||
        fail "np $p threads $t: other files than the one-process run's"
      for f in $files; do cmp "$work/one/$f" "$out/$f" || fail "np $p threads $t: $f differs"; done
      grep -q "\"processes\": $p," "$out/run_info.json" || fail "np $p: run_info.json does not say $p processes"
      if [ "$p" -gt 1 ]; then
        grep -q "\"partition\": {\"points\": \[" "$out/run_info.json" || fail "np $p: no partition in run_info.json"
        grep -q "^distributed run, $p processes: points " "$out/log.txt" || fail "np $p: no partition in log.txt"
      fi
      echo "np $p threads $t: $(echo "$files" | wc -l) files identical"
    done
  done
  ;;
checkpoint)
  # distributed_solve.sh checkpoint ... WORK_DIR WRITERS CONTINUERS... [-- OPTIONS...]: a run with
  # checkpoints every 2 us on WRITERS processes; its checkpoint (the last, before the end) and its
  # files are the one-process run's; continued from it (--restart) on each number of CONTINUERS
  # processes (1: without mpirun), the run directory is the uninterrupted one-process run's again.
  writers=$1
  shift
  continuers=
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do continuers="$continuers $1"; shift; done
  [ $# -gt 0 ] && shift
  set -- --set output.checkpoint_interval=2us "$@"
  "$bin/mppm-solve" "$scene" --points "$work/points.vtp" -o "$work/one" --quiet "$@" || fail "the one-process run"
  files=$(cd "$work/one" && find . -type f ! -name log.txt ! -name run_info.json | sort)
  echo "$files" | grep -q '^./checkpoint/state.ckpt$' || fail "the one-process run wrote no checkpoint"
  run_mpi "$writers" 2 "$scene" --points "$work/points.vtp" -o "$work/written" "$@" ||
    { cat "$work/err.txt"; fail "the run on $writers processes"; }
  for f in $files; do cmp "$work/one/$f" "$work/written/$f" || fail "written on $writers processes: $f differs"; done
  for p in $continuers; do
    out="$work/continued_on_$p"
    cp -r "$work/written" "$out"
    if [ "$p" -eq 1 ]; then
      "$bin/mppm-solve" --restart "$out" --quiet 2> "$work/err.txt"
    else
      run_mpi "$p" 1 --restart "$out"
    fi || { cat "$work/err.txt"; fail "continued on $p"; }
    grep -q "^mppm-solve .* --restart: continues from .*(step [1-9]" "$out/log.txt" ||
      fail "continued on $p: the log does not say where it continued from"
    for f in $files; do cmp "$work/one/$f" "$out/$f" || fail "written on $writers, continued on $p: $f differs"; done
    echo "written on $writers processes, continued on $p: $(echo "$files" | wc -l) files identical"
  done
  ;;
nan)
  last=$(($(grep -a -o 'NumberOfPoints="[0-9]*"' "$work/points.vtp" | head -1 | tr -dc 0-9) - 1))
  run_mpi 3 2 "$scene" --points "$work/points.vtp" -o "$work/run" --inject-nan "5:$last"
  code=$?
  cat "$work/err.txt"
  test $code -eq 3 || fail "exit $code, expected 3"
  test "$(mppm_lines)" -eq 1 || fail "expected one message"
  grep -q "numerical failure at step 5, .*non-finite velocity at point $last of the points file.*on process 2 of 3" \
    "$work/err.txt" || fail "the message does not name point $last on process 2 at step 5"
  grep -q '"status": "numerical_failure"' "$work/run/run_info.json" || fail "run_info.json status"
  ;;
refused)
  # distributed_solve.sh refused ... WORK_DIR EXPECTED [ARGS...]: the message must hold EXPECTED.
  expected=$1
  shift
  run_mpi 2 1 "$scene" --points "$work/points.vtp" -o "$work/run" "$@"
  code=$?
  cat "$work/err.txt"
  test $code -eq 2 || fail "exit $code, expected 2"
  test "$(mppm_lines)" -eq 1 || fail "expected one message"
  grep -q "$expected" "$work/err.txt" || fail "the message does not say '$expected'"
  test ! -e "$work/run" || fail "a run directory was written"
  ;;
taken)
  # The run directory exists: the first process's refusal to write it reaches the other.
  mkdir -p "$work/taken" && touch "$work/taken/mine.txt"
  run_mpi 2 1 "$scene" --points "$work/points.vtp" -o "$work/taken"
  code=$?
  cat "$work/err.txt"
  test $code -eq 2 || fail "exit $code, expected 2"
  test "$(mppm_lines)" -eq 1 || fail "expected one message"
  grep -q "already exists" "$work/err.txt" || fail "the existing run directory is not named"
  test "$(ls "$work/taken")" = mine.txt || fail "the existing run directory was changed"
  ;;
interrupt)
  OMP_NUM_THREADS=1 "$mpiexec" --oversubscribe --bind-to none -np 3 "$bin/mppm-solve" "$scene" \
    --points "$work/points.vtp" -o "$work/run" --set time.end=50ms --set output.interval=10ms --quiet \
    2> "$work/err.txt" &
  launcher=$!
  # Signalled once the time loop runs (run_info.json is written with the snapshot of t = 0).
  for _ in $(seq 300); do test -f "$work/run/run_info.json" && break; sleep 0.1; done
  sleep 1
  kill -TERM $launcher
  wait $launcher
  code=$?
  cat "$work/err.txt"
  test $code -eq 1 || fail "exit $code, expected 1 (interrupted)"
  test "$(mppm_lines)" -eq 1 || fail "expected one message"
  grep -q '"status": "interrupted"' "$work/run/run_info.json" || fail "run_info.json status"
  step=$(sed -n 's/^interrupted at step \([0-9]*\) .*/\1/p' "$work/run/log.txt")
  test -n "$step" || fail "log.txt does not say where the run stopped"
  test -f "$work/run/snapshots/snapshot_$(printf %06d "$step").snap" || fail "no snapshot of step $step"
  ;;
*) fail "unknown mode $mode" ;;
esac
echo "ok"
