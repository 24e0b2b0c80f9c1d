#!/usr/bin/env bash
# `make test-cluster`: the test campaign (tests/config_small.yaml) on a real single-node SLURM of this
# host, through profiles/slurm, and its arrays against a local run of the same configuration.
#   1. installs Debian's slurm-wlm and munge when missing (root, apt);
#   2. writes /etc/slurm/slurm.conf for this host (2 CPUs, no cgroups, no accounting): the plugin's job
#      steps drop SLURM_CONF, so the configuration must be at the default path;
#   3. starts munged, slurmctld and slurmd in the foreground of background shells, waits for the node
#      to be idle, runs the campaign, compares, and on exit stops every daemon it started, by PID.
# Usage: .ci/slurm/test_cluster.sh VENV_BIN WORKDIR
set -euo pipefail
BIN=$(realpath "$1")
WORK=$(realpath -m "$2")
REPO=$(cd "$(dirname "$0")/../.." && pwd)
CONF=/etc/slurm/slurm.conf
MARK="# ringdamper single-node test cluster"
NODE=$(hostname -s)
PIDS=()

log() { printf '[test-cluster %s] %s\n' "$(date -u +%H:%M:%S)" "$*"; }

stop_daemons() {
    for pid in "${PIDS[@]}"; do
        kill "$pid" 2>/dev/null || true
    done
    for pid in "${PIDS[@]}"; do
        for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
        kill -9 "$pid" 2>/dev/null || true
    done
    [ ${#PIDS[@]} -eq 0 ] || log "stopped daemons ${PIDS[*]}"
}
trap stop_daemons EXIT

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    log "installing slurm-wlm and munge"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq slurm-wlm munge >/dev/null
fi
if pgrep -x slurmctld >/dev/null || pgrep -x slurmd >/dev/null; then
    echo "a slurmctld or slurmd is already running (PIDs $(pgrep -x slurmctld) $(pgrep -x slurmd)): stop it first" >&2
    exit 1
fi
if [ -e "$CONF" ] && ! head -n 1 "$CONF" | grep -qF "$MARK"; then
    echo "$CONF exists and was not written by this script: not overwriting it" >&2
    exit 1
fi

STATE="$WORK/slurm"
rm -rf "$STATE" "$WORK/slurm_results" "$WORK/local_results" && mkdir -p "$STATE/ctld" "$STATE/spool" "$STATE/log"
MEM_MB=$(awk '/MemTotal/ {print int($2 / 1024 * 0.8)}' /proc/meminfo)
cat > "$CONF" <<CONFEOF
$MARK (written by .ci/slurm/test_cluster.sh)
ClusterName=ringdamper
SlurmctldHost=$NODE(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
StateSaveLocation=$STATE/ctld
SlurmdSpoolDir=$STATE/spool
SlurmctldPidFile=$STATE/slurmctld.pid
SlurmdPidFile=$STATE/slurmd.pid
SlurmctldLogFile=$STATE/log/slurmctld.log
SlurmdLogFile=$STATE/log/slurmd.log
ReturnToService=2
MpiDefault=none
NodeName=$NODE NodeAddr=127.0.0.1 CPUs=2 RealMemory=$MEM_MB State=UNKNOWN
PartitionName=main Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
CONFEOF

log "starting munged, slurmctld, slurmd"
install -d -o munge -g munge -m 0755 /run/munge
setpriv --reuid=munge --regid=munge --init-groups /usr/sbin/munged -F >"$STATE/log/munged.out" 2>&1 &
PIDS+=($!)
for _ in $(seq 50); do [ -S /run/munge/munge.socket.2 ] && break; sleep 0.2; done
/usr/sbin/slurmctld -D -f "$CONF" >"$STATE/log/slurmctld.out" 2>&1 &
PIDS+=($!)
/usr/sbin/slurmd -D -f "$CONF" >"$STATE/log/slurmd.out" 2>&1 &
PIDS+=($!)
for i in $(seq 60); do
    state=$(sinfo -h -n "$NODE" -o %T 2>/dev/null || true)
    [ "$state" = idle ] && break
    [ "$i" -lt 60 ] || { echo "node not idle after 60 s (state: '$state'); logs in $STATE/log" >&2; exit 1; }
    sleep 1
done
log "node $NODE idle"

SMK=("$BIN/python" -m snakemake --snakefile "$REPO/Snakefile" --directory "$REPO"
     --configfile "$REPO/tests/config_small.yaml")
cd "$REPO"
# A crash midway: once KILL_AFTER cluster jobs have finished, the submitting Snakemake is killed
# (SIGKILL) and the jobs it left in SLURM are cancelled. The resumed run (--unlock, then the profile's
# --rerun-incomplete) must run no job again that Snakemake had recorded as finished (its log maps each
# jobid to its benchmark file, written last by the job: those files must keep their timestamps; a job
# that ended in SLURM after the last status check is rightly run again) and end with the arrays of the
# local run.
KILL_AFTER=${KILL_AFTER:-8}
start=$(date +%s)
"${SMK[@]}" --workflow-profile profiles/slurm --config "results=$WORK/slurm_results" > "$WORK/slurm_killed.log" 2>&1 &
smk=$!
until [ "$(grep -c '^Finished jobid' "$WORK/slurm_killed.log" || true)" -ge "$KILL_AFTER" ] || ! kill -0 "$smk" 2>/dev/null; do
    sleep 1
done
kill -9 "$smk" 2>/dev/null || { echo "the SLURM run ended before $KILL_AFTER jobs finished" >&2; tail -40 "$WORK/slurm_killed.log"; exit 1; }
wait "$smk" 2>/dev/null || true
scancel --user "$(id -un)" || true
awk '/jobid: [0-9]+$/ {id = $NF} /benchmark: / {bench[id] = $NF}
     /^Finished jobid:/ {done[$3] = 1} END {for (i in done) if (i in bench) print bench[i]}' \
    "$WORK/slurm_killed.log" | sort | while read -r path; do printf '%s %s\n' "$path" "$(find "$path" -printf '%T@')"; done \
    > "$WORK/finished_before_kill.txt"
log "SLURM run killed after $(( $(date +%s) - start )) s, $(wc -l < "$WORK/finished_before_kill.txt") jobs recorded as finished"
"${SMK[@]}" --workflow-profile profiles/slurm --config "results=$WORK/slurm_results" --unlock > /dev/null 2>&1
"${SMK[@]}" --workflow-profile profiles/slurm --config "results=$WORK/slurm_results" > "$WORK/slurm_run.log" 2>&1 \
    || { tail -40 "$WORK/slurm_run.log"; exit 1; }
rerun=$(while read -r path stamp; do
            [ "$(find "$path" -printf '%T@')" = "$stamp" ] || echo "$path"
        done < "$WORK/finished_before_kill.txt")
[ -z "$rerun" ] || { echo "finished jobs ran again after the resume: $rerun" >&2; exit 1; }
log "SLURM run resumed: $(grep -c 'submitted with SLURM jobid' "$WORK/slurm_run.log" || true) cluster jobs for the rest, \
no finished job again; $(( $(date +%s) - start )) s in all"
log "resumed run: $("$BIN/python" -m tools.slurm_overhead "$STATE/log/slurmctld.log" "$WORK/slurm_run.log")"
start=$(date +%s)
"${SMK[@]}" --workflow-profile profiles/default --config "results=$WORK/local_results" > "$WORK/local_run.log" 2>&1 \
    || { tail -40 "$WORK/local_run.log"; exit 1; }
log "local run: $(( $(date +%s) - start )) s"
"$BIN/python" -m tools.compare_results "$WORK/slurm_results" "$WORK/local_results"
