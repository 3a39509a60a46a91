#!/usr/bin/env bash
# A real single-node Slurm cluster (munged + slurmctld + slurmd, Debian 12
# packages, no systemd, no cgroups) for testing `hapcine batch --slurm`.
#
#   slurm_test_cluster.sh up DIR      start a cluster whose files all live in DIR;
#                                     prints the SLURM_CONF to export
#   slurm_test_cluster.sh down DIR    stop it (by the pids in DIR's pid files)
#   slurm_test_cluster.sh test HAPCINE_EXE
#                                     the ctest test (label slurm): start a
#                                     cluster; run a library (stand-in steps)
#                                     locally and as a job array, check both give
#                                     the same outputs, re-run (everything
#                                     skipped); then the same with the real
#                                     pipeline on synthetic clips and bad files;
#                                     stop
#
# Exit codes of `test`: 0 passed, 1 failed (including a Slurm that is installed
# but does not start), 77 skipped (Slurm not installed, or not root); the
# reason is printed. Daemons are
# stopped on every path (trap), never by name. Set HAPCINE_SLURM_KEEP=1 to keep
# the temporary folder for inspection.
set -euo pipefail

SKIP=77
log() { echo "slurm_test_cluster: $*" >&2; }
skip() { log "SKIP: $*"; exit $SKIP; }
fail() { log "FAIL: $*"; exit 1; }

# ---------------------------------------------------------------- cluster ---

# Stops what DIR's pid files name; waits up to 5 s, then SIGKILL.
cluster_down() {
  local dir=$1 f pid i
  for f in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munge/munged.pid"; do
    [ -s "$f" ] || continue
    pid=$(cat "$f" 2>/dev/null || true)
    [[ "$pid" =~ ^[0-9]+$ ]] || continue
    kill "$pid" 2>/dev/null || continue
    for i in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
    rm -f "$f"
  done
}

free_port() {  # a TCP port nobody listens on, from a range unlikely to clash
  local p
  for _ in $(seq 50); do
    p=$((20000 + RANDOM % 20000))
    if ! (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null; then echo "$p"; return; fi
  done
  echo 26817
}

# Starts the cluster in DIR (must exist). Returns 77 with a reason where Slurm
# is not installed or cannot be run (not root); 1 if it is installed but does
# not start (a real failure, never hidden as a skip).
cluster_up() {
  local dir=$1
  for prog in munged munge slurmctld slurmd sinfo sbatch squeue; do
    command -v "$prog" >/dev/null || { log "$prog not installed (run scripts/install_deps.sh)"; return $SKIP; }
  done
  [ "$(id -u)" -eq 0 ] || { log "needs root to start slurmd/slurmctld and munged"; return $SKIP; }
  getent passwd munge >/dev/null || { log "no 'munge' user (munge package incomplete)"; return $SKIP; }
  [ -r /etc/munge/munge.key ] || { log "no /etc/munge/munge.key"; return $SKIP; }

  # munged refuses sockets in folders others can write or cannot reach.
  chmod 755 "$dir"
  mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/log"
  chown munge:munge "$dir/munge"
  chmod 755 "$dir/munge"
  local socket=$dir/munge/munge.socket
  if ! runuser -u munge -- munged --socket="$socket" --pid-file="$dir/munge/munged.pid" \
        --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed" \
        >"$dir/log/munged.out" 2>&1; then
    log "munged did not start: $(tail -n1 "$dir/log/munged.out")"
    return 1
  fi
  munge -n -S "$socket" | unmunge -S "$socket" >/dev/null 2>&1 \
    || { log "munge credential round-trip failed"; return 1; }

  local cpus ctld_port d_port
  cpus=$(nproc)
  ctld_port=$(free_port)
  d_port=$(free_port)
  [ "$d_port" != "$ctld_port" ] || d_port=$((ctld_port + 1))
  cat >"$dir/slurm.conf" <<EOF
# Single-node test cluster written by scripts/slurm_test_cluster.sh
ClusterName=hapcinetest
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF=$dir/slurm.conf
  if ! slurmctld >"$dir/log/slurmctld.out" 2>&1; then
    log "slurmctld did not start: $(tail -n1 "$dir/log/slurmctld.log" 2>/dev/null)"
    return 1
  fi
  if ! slurmd -N localhost >"$dir/log/slurmd.out" 2>&1; then
    log "slurmd did not start: $(tail -n1 "$dir/log/slurmd.log" 2>/dev/null)"
    return 1
  fi
  local state=""
  for _ in $(seq 150); do
    state=$(sinfo -h -n localhost -o %T 2>/dev/null || true)
    [ "$state" = idle ] && break
    sleep 0.2
  done
  if [ "$state" != idle ]; then
    log "node not idle after 30 s (state '$state'): $(tail -n1 "$dir/log/slurmd.log" 2>/dev/null)"
    return 1
  fi
  log "cluster up in $dir (node localhost, $cpus CPUs, slurmctld port $ctld_port)"
}

# ------------------------------------------------------------------- test ---

# Stand-in for `hapcine estimate|haptics` (same contract as the unit tests'):
# outputs depend only on the input bytes; bad inputs fail with one line.
write_fake_step() {
  cat >"$1" <<'EOF'
#!/bin/bash
set -u
cmd=$1; shift
case "$cmd" in
  estimate)
    in=$1; out=$3
    sleep "${FAKE_ESTIMATE_DELAY:-0.2}"
    IFS= read -r -d '' content < "$in"
    if [[ $content == *corrupt* ]]; then echo "hapcine estimate: $in: corrupt video stream" >&2; exit 1; fi
    if [[ $content != FAKEVIDEO* ]]; then echo "hapcine estimate: $in: no video stream found" >&2; exit 1; fi
    printf 'frame,time_s\n%s\nhost-independent\n' "$content" > "$out" ;;
  haptics)
    cam=$1; model=$3; out=$5; hjif=$7
    IFS= read -r -d '' camera < "$cam"
    printf 'model,%s\n%s' "$model" "$camera" > "$out"
    echo "{\"model\":\"$model\"}" > "$hjif" ;;
  *) echo "unknown command $cmd" >&2; exit 2 ;;
esac
EOF
  chmod 755 "$1"
}

make_library() {
  local lib=$1
  mkdir -p "$lib/sub dir"
  for n in a.mp4 b.mov "c d.mkv" "é clip.mp4" "日本.mkv" "sub dir/e.webm"; do
    echo "FAKEVIDEO $n" >"$lib/$n"
  done
  echo "FAKEVIDEO a.mp4" >"$lib/zz copy of a.mp4"   # duplicate of a.mp4
  echo "FAKEVIDEO corrupt" >"$lib/corrupt.mp4"
  : >"$lib/empty.mp4"
  echo "shopping list" >"$lib/notes.mp4"
  echo "not a video" >"$lib/readme.txt"
}

# "done skipped failed duplicate" of a summary.json
counts() {
  python3 -c 'import json,sys; c=json.load(open(sys.argv[1]))["counts"]; print(c["done"], c["skipped"], c["failed"], c["duplicate"])' "$1"
}

# Lists output files (relative path + checksum) of an output folder.
outputs() {
  (cd "$1" && find . -type f \( -name '*.camera.csv' -o -name '*.haptic.csv' -o -name '*.hjif' \) \
     -not -path '*/.tmp/*' -print0 | sort -z | xargs -0 -r sha256sum)
}

# A job array cancelled midway (scancel: tasks and their steps killed) and
# submitted again must finish the films left, skip the ones done, and give
# the same outputs as the local run, with no temporary left behind.
cancel_resume_test() {
  local exe=$1 fake=$2 out=$WORK/cancel
  log "Slurm run cancelled midway (scancel), then submitted again"
  FAKE_ESTIMATE_DELAY=2 "$exe" batch "$WORK/library" -o "$out" --slurm --shards 2 --jobs 1 \
    --no-wait --hapcine-exe "$fake" 2>"$WORK/cancel.err" || { cat "$WORK/cancel.err" >&2; fail "submit"; }
  local job
  job=$(tail -n1 "$out/slurm/sbatch.log" | cut -d';' -f1)
  [[ "$job" =~ ^[0-9]+$ ]] || fail "no job id in $out/slurm/sbatch.log"
  local n=0
  for _ in $(seq 600); do
    n=$(find "$out" -mindepth 2 -maxdepth 2 -name done.json | wc -l)
    [ "$n" -ge 1 ] && break
    sleep 0.1
  done
  [ "$n" -ge 1 ] || fail "no film finished within 60 s of submission"
  scancel "$job" || fail "scancel $job"
  for _ in $(seq 300); do
    [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] && break
    sleep 0.1
  done
  [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] || fail "job $job still queued 30 s after scancel"
  sleep 0.5  # killed steps go
  n=$(find "$out" -mindepth 2 -maxdepth 2 -name done.json | wc -l)
  [ "$n" -lt 6 ] || fail "scancel came too late to test (all 6 films done)"
  "$exe" batch --status "$out" | grep -q "pending" || fail "status after scancel: $("$exe" batch --status "$out")"

  local rc=0
  "$exe" batch "$WORK/library" -o "$out" --slurm --shards 2 --jobs 1 --hapcine-exe "$fake" \
    2>"$WORK/cancel2.err" || rc=$?
  [ $rc -eq 1 ] || { cat "$WORK/cancel2.err" >&2; fail "re-submission exit $rc"; }
  [ "$(counts "$out/summary.json")" = "$((6 - n)) $n 3 1" ] \
    || fail "after scancel + re-submission: counts $(counts "$out/summary.json"), expected $((6 - n)) $n 3 1"
  outputs "$out" | diff "$WORK/local.sums" - >&2 || fail "outputs after scancel + re-submission differ from the local run's"
  local left
  left=$(find "$out" \( -name .tmp -o -name '*.tmp-*' -o -name '*.hapcine-tmp' \) | head -n3)
  [ -z "$left" ] || fail "temporaries left: $left"
  log "cancelled with $n of 6 films done; re-submission did the other $((6 - n)), outputs equal the local run's"
}

# The real pipeline (synth -> estimate -> haptics) on a library of two
# synthetic clips under awkward names plus a duplicate, a truncated clip, a
# zero-byte file and a text file named .mp4: locally and as a 2-task array.
# Every output (camera path, haptic tracks, .hjif) and every failure reason
# must be the same; the outputs record the camera path they were made from
# (inside OUT_DIR), so the two output folders' paths are masked first.
real_pipeline_test() {
  local exe=$1 real=$WORK/real
  mkdir -p "$real/src" "$real/lib/sub dir"
  local presets
  presets=$("$exe" synth --list 2>/dev/null | awk 'NR<=2 {print $1}' | tr '\n' ' ')
  [ -n "$presets" ] || fail "real pipeline: hapcine synth --list gave no presets"
  # shellcheck disable=SC2086  # two preset names
  "$exe" synth $presets -o "$real/src" --width 320 --height 180 --duration-s 1 >"$real/synth.log" 2>&1 \
    || fail "real pipeline: could not render synthetic clips: $(tail -n1 "$real/synth.log")"
  local clips=("$real"/src/*.mp4)
  [ ${#clips[@]} -ge 2 ] || fail "real pipeline: synth wrote ${#clips[@]} clips, expected 2"
  cp "${clips[0]}" "$real/lib/clip one.mp4"
  cp "${clips[1]}" "$real/lib/sub dir/日本 é.mp4"
  cp "${clips[0]}" "$real/lib/zz copy of clip one.mp4"       # duplicate
  head -c 3000 "${clips[1]}" >"$real/lib/truncated.mp4"       # corrupt
  : >"$real/lib/empty.mp4"                                     # zero bytes
  echo "shopping list" >"$real/lib/notes.mp4"                  # not a video

  log "real pipeline: local run"
  local rc=0 t1=$SECONDS
  "$exe" batch "$real/lib" -o "$real/local" --jobs 2 --progress lines 2>"$real/local.err" || rc=$?
  [ $rc -eq 1 ] || { cat "$real/local.err" >&2; fail "real local batch exit $rc (expected 1: 3 bad files)"; }
  [ "$(counts "$real/local/summary.json")" = "2 0 3 1" ] \
    || { cat "$real/local.err" >&2; fail "real local counts $(counts "$real/local/summary.json"), expected 2 done 0 skipped 3 failed 1 duplicate"; }
  local t_local=$((SECONDS - t1))

  log "real pipeline: 2-task job array"
  rc=0 t1=$SECONDS
  "$exe" batch "$real/lib" -o "$real/slurm" --slurm --shards 2 --jobs 1 2>"$real/slurm.err" || rc=$?
  [ $rc -eq 1 ] || { cat "$real/slurm.err" >&2; fail "real Slurm batch exit $rc (expected 1)"; }
  [ "$(counts "$real/slurm/summary.json")" = "2 0 3 1" ] \
    || fail "real Slurm counts $(counts "$real/slurm/summary.json"), expected 2 0 3 1"
  local t_slurm=$((SECONDS - t1))

  masked_outputs "$real/local" >"$real/local.sums"
  masked_outputs "$real/slurm" >"$real/slurm.sums"
  [ "$(wc -l <"$real/local.sums")" -eq 10 ] \
    || fail "real pipeline: expected 10 output files (2 films x camera + 2 models x 2), got $(wc -l <"$real/local.sums")"
  diff "$real/local.sums" "$real/slurm.sums" >&2 || fail "real pipeline: Slurm outputs differ from the local run's"
  reasons "$real/local/summary.json" >"$real/local.reasons"
  reasons "$real/slurm/summary.json" >"$real/slurm.reasons"
  diff "$real/local.reasons" "$real/slurm.reasons" >&2 || fail "real pipeline: failure reasons differ"
  log "real pipeline: 10 outputs and 3 failure reasons identical (local ${t_local} s, job array ${t_slurm} s)"
}

# sha256 of every output file with the output folder's own path masked.
masked_outputs() {
  local dir=$1 f
  (cd "$dir" && find . -type f \( -name '*.camera.csv' -o -name '*.haptic.csv' -o -name '*.hjif' \) \
     -not -path '*/.tmp/*' -print0 | sort -z) |
    while IFS= read -r -d '' f; do
      printf '%s  %s\n' "$(sed "s|$dir|OUT_DIR|g" "$dir/$f" | sha256sum | cut -d' ' -f1)" "$f"
    done
}

# "status id reason" per film of a summary.json.
reasons() {
  python3 -c 'import json,sys; [print(f["status"], f["id"], f["reason"]) for f in json.load(open(sys.argv[1]))["films"]]' "$1"
}

run_test() {
  local exe=${1:?usage: slurm_test_cluster.sh test HAPCINE_EXE}
  exe=$(readlink -f "$exe")
  [ -x "$exe" ] || fail "no executable $exe"
  local t0=$SECONDS
  WORK=$(mktemp -d /tmp/hapcine_slurm_XXXXXX)
  trap 'cluster_down "$WORK/cluster"; [ "${HAPCINE_SLURM_KEEP:-0}" = 1 ] && log "kept $WORK" || rm -rf "$WORK"' EXIT
  chmod 755 "$WORK"  # munged (user munge) must reach its socket folder
  mkdir -p "$WORK/cluster"
  local rc=0
  cluster_up "$WORK/cluster" || rc=$?
  [ $rc -eq 0 ] || { [ $rc -eq $SKIP ] && skip "Slurm cannot run here (see above)"; fail "Slurm is installed but the cluster did not start (logs: $WORK/cluster/log, kept with HAPCINE_SLURM_KEEP=1)"; }
  export SLURM_CONF=$WORK/cluster/slurm.conf
  local t_up=$((SECONDS - t0))

  local fake=$WORK/fake-hapcine
  write_fake_step "$fake"
  make_library "$WORK/library"

  log "local run"
  rc=0
  "$exe" batch "$WORK/library" -o "$WORK/local" --hapcine-exe "$fake" --jobs 2 --progress lines \
    2>"$WORK/local.err" || rc=$?
  [ $rc -eq 1 ] || { cat "$WORK/local.err" >&2; fail "local batch exit $rc (expected 1: 3 bad films)"; }
  [ "$(counts "$WORK/local/summary.json")" = "6 0 3 1" ] \
    || fail "local counts $(counts "$WORK/local/summary.json"), expected 6 done 0 skipped 3 failed 1 duplicate"

  log "Slurm run: 3-task job array"
  local t1=$SECONDS
  rc=0
  "$exe" batch "$WORK/library" -o "$WORK/slurm" --slurm --shards 3 --jobs 1 \
    --hapcine-exe "$fake" 2>"$WORK/slurm.err" || rc=$?
  cat "$WORK/slurm.err" >&2
  [ $rc -eq 1 ] || fail "slurm batch exit $rc (expected 1: 3 bad films)"
  local t_array=$((SECONDS - t1))
  for i in 0 1 2; do
    [ -s "$WORK/slurm/slurm/task-$i.status" ] || fail "task $i wrote no status file"
    grep -q "batch: \[" "$WORK/slurm/slurm/task-$i.log" || fail "task $i log has no progress lines"
  done
  [ "$(counts "$WORK/slurm/summary.json")" = "6 0 3 1" ] \
    || fail "slurm counts $(counts "$WORK/slurm/summary.json"), expected 6 0 3 1"
  outputs "$WORK/local" >"$WORK/local.sums"
  outputs "$WORK/slurm" >"$WORK/slurm.sums"
  [ "$(wc -l <"$WORK/local.sums")" -eq 30 ] || fail "expected 30 output files, got $(wc -l <"$WORK/local.sums")"
  diff "$WORK/local.sums" "$WORK/slurm.sums" >&2 || fail "Slurm outputs differ from the local run's"
  "$exe" batch --status "$WORK/slurm" | grep -q "10 films: 6 done, 3 failed, 1 duplicate, 0 running, 0 pending" \
    || fail "status: $("$exe" batch --status "$WORK/slurm")"

  log "Slurm re-run: everything up to date must be skipped"
  rc=0
  "$exe" batch "$WORK/library" -o "$WORK/slurm" --slurm --shards 3 --jobs 1 \
    --hapcine-exe "$fake" 2>"$WORK/slurm2.err" || rc=$?
  [ $rc -eq 1 ] || { cat "$WORK/slurm2.err" >&2; fail "slurm re-run exit $rc"; }
  [ "$(counts "$WORK/slurm/summary.json")" = "0 6 3 1" ] \
    || fail "re-run counts $(counts "$WORK/slurm/summary.json"), expected 0 6 3 1"
  outputs "$WORK/slurm" | diff "$WORK/local.sums" - >&2 || fail "re-run changed outputs"

  cancel_resume_test "$exe" "$fake"
  real_pipeline_test "$exe"
  log "PASS in $((SECONDS - t0)) s (cluster up ${t_up} s, first job array ${t_array} s)"
}

case "${1:-}" in
  up)
    [ -n "${2:-}" ] || { echo "usage: $0 up DIR" >&2; exit 2; }
    mkdir -p "$2"
    dir=$(readlink -f "$2")
    rc=0
    cluster_up "$dir" || rc=$?
    if [ $rc -ne 0 ]; then cluster_down "$dir"; exit $rc; fi
    echo "export SLURM_CONF=$dir/slurm.conf"
    ;;
  down)
    [ -n "${2:-}" ] || { echo "usage: $0 down DIR" >&2; exit 2; }
    cluster_down "$(readlink -f "$2")"
    ;;
  test) shift; run_test "$@" ;;
  *) echo "usage: $0 up DIR | down DIR | test HAPCINE_EXE" >&2; exit 2 ;;
esac
