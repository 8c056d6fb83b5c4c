#!/usr/bin/env bash
# Smoke test of scripts/sweep.sbatch against a real Slurm: a one-node cluster on this machine.
#
#   sudo bash scripts/slurm-smoke.sh
#
# It installs Debian's slurm-wlm and munge if missing (needs root), writes a one-node
# slurm.conf into a temporary directory (no cgroup plugins, so it works in a container), starts
# munged, slurmctld and slurmd there, submits sweep.sbatch as an array job over a small grid,
# waits for it, merges, runs the same grid locally with `steplearn sweep` (no shards) + `merge`,
# and compares the two ablation tables byte for byte, except the run-time columns (wall times
# differ between any two runs): the last column of ablation.md ("run time (s)") and the last two
# of ablation.csv (run_time_s_mean, run_time_s_std) are stripped before comparing. It stops
# every daemon it started. Its last line is `identical` (exit 0) or what differs (exit 1).
#
# Environment: STEPLEARN_BIN (default: target/release/steplearn, built if absent),
# SMOKE_SHARDS (array size, default 4), SMOKE_SEEDS (1), SMOKE_PUSHES (5),
# SMOKE_KEEP=1 keeps the temporary directory (it is always kept on failure).
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
shards=${SMOKE_SHARDS:-4}
seeds=${SMOKE_SEEDS:-1}
pushes=${SMOKE_PUSHES:-5}
ncpu=$(nproc)
start=$(date +%s)
say() { echo "[slurm-smoke $(($(date +%s) - start))s] $*" >&2; }

# --- packages -----------------------------------------------------------------------------
need=()
for c in slurmctld slurmd sbatch squeue sinfo scancel; do
    command -v "$c" >/dev/null || need=(slurm-wlm)
done
command -v munged >/dev/null || need+=(munge)
if ((${#need[@]})); then
    if (($(id -u) != 0)); then
        echo "slurm-smoke: ${need[*]} missing and not root: run as root (sudo bash $0)" \
            "or install them first (apt-get install slurm-wlm munge)" >&2
        exit 1
    fi
    say "installing ${need[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi
if (($(id -u) != 0)); then
    echo "slurm-smoke: slurmd must run as root (it starts jobs as their user): run as root" >&2
    exit 1
fi

# --- the binary ---------------------------------------------------------------------------
bin=${STEPLEARN_BIN:-${CARGO_TARGET_DIR:-$repo/target}/release/steplearn}
if [[ ! -x $bin ]]; then
    say "building $bin"
    (cd "$repo" && cargo build --release --quiet)
fi
bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")

# --- one-node configuration in a temporary directory --------------------------------------
tmp=$(mktemp -d /tmp/slurm-smoke.XXXXXX)
chmod 755 "$tmp"
mkdir -p "$tmp"/{munge,state,spool,out}
chmod 700 "$tmp/munge"
host=$(hostname -s)
# Slightly below MemTotal, so slurmd never finds less memory than configured (node INVALID).
mem_mb=$(awk '/^MemTotal:/ { printf "%d", $2 / 1024 * 0.95 }' /proc/meminfo)
conf=$tmp/slurm.conf
cat >"$conf" <<EOF
ClusterName=smoke
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=16817
SlurmdPort=16818
AuthType=auth/munge
AuthInfo=socket=$tmp/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MaxArraySize=1001
NodeName=$host NodeAddr=127.0.0.1 CPUs=$ncpu RealMemory=$mem_mb State=UNKNOWN
PartitionName=smoke Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$conf

pids=()
jobid=
cleanup() {
    local rc=$?
    set +e
    if [[ -n $jobid ]]; then
        scancel "$jobid" 2>/dev/null
        sleep 1
    fi
    # Stop in reverse order: slurmd, slurmctld, munged.
    for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
        kill "${pids[i]}" 2>/dev/null
    done
    for p in "${pids[@]}"; do
        wait "$p" 2>/dev/null
    done
    # Kept on failure (the failure message names it) or with SMOKE_KEEP=1; nothing is printed
    # here so that the last line stays `identical` or what differs.
    if ((rc == 0)) && [[ ${SMOKE_KEEP:-0} != 1 ]]; then
        rm -rf "$tmp"
    fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# --- daemons ------------------------------------------------------------------------------
if command -v mungekey >/dev/null; then
    mungekey --create --keyfile="$tmp/munge/munge.key" --force
else
    dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1024 count=1 status=none
fi
chmod 400 "$tmp/munge/munge.key"
say "starting munged, slurmctld, slurmd (configuration and logs in $tmp)"
munged --foreground --force --key-file="$tmp/munge/munge.key" \
    --socket="$tmp/munge/munge.socket" --pid-file="$tmp/munge/munged.pid" \
    --log-file="$tmp/munge/munged.log" --seed-file="$tmp/munge/munged.seed" \
    >"$tmp/munged.out" 2>&1 &
pids+=($!)
for _ in $(seq 50); do
    [[ -S $tmp/munge/munge.socket ]] && break
    sleep 0.2
done
slurmctld -D -c -i -f "$conf" >"$tmp/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$conf" -N "$host" >"$tmp/slurmd.out" 2>&1 &
pids+=($!)

state=
for _ in $(seq 60); do
    state=$(sinfo -h -N -n "$host" -o '%T' 2>/dev/null || true)
    [[ $state == idle ]] && break
    sleep 1
done
if [[ $state != idle ]]; then
    tail -n 20 "$tmp"/*.log "$tmp"/*.out >&2 || true
    echo "node $host is not idle after 60 s (state: ${state:-none}); logs in $tmp"
    exit 1
fi
say "node $host idle ($ncpu CPUs, ${mem_mb} MB)"

# --- the array job ------------------------------------------------------------------------
slurm_out=$tmp/slurm-sweep
local_out=$tmp/local-sweep
# --no-requeue: a task that cannot start fails (and is reported below) instead of waiting held.
jobid=$(sbatch --parsable --no-requeue --array="0-$((shards - 1))" --cpus-per-task=1 \
    --time=00:30:00 \
    --chdir="$repo" --output="$tmp/out/shard-%a.out" \
    --export="ALL,STEPLEARN_BIN=$bin,STEPLEARN_OUT=$slurm_out,STEPLEARN_SEEDS=$seeds,STEPLEARN_PUSHES=$pushes" \
    "$repo/scripts/sweep.sbatch")
jobid=${jobid%%;*}
say "submitted array job $jobid: $shards shards, --seeds $seeds --pushes $pushes"
deadline=$(($(date +%s) + 1200))
while [[ -n $(squeue -h -j "$jobid" -o '%i' 2>/dev/null) ]]; do
    if (($(date +%s) > deadline)); then
        echo "array job $jobid still queued or running after 20 min; logs in $tmp"
        exit 1
    fi
    # A drained node (e.g. a full disk under SlurmdSpoolDir) never runs the remaining tasks.
    reason=$(sinfo -h -R -n "$host" -o '%E' 2>/dev/null || true)
    if [[ -n $reason ]]; then
        echo "node $host drained ($reason) while job $jobid ran; logs in $tmp"
        exit 1
    fi
    sleep 2
done
job_done=$jobid
jobid=
say "array job $job_done finished"
for ((i = 0; i < shards; i++)); do
    f=$tmp/out/shard-$i.out
    if [[ ! -f $f ]] || [[ $(tail -n 1 "$f") != "steplearn-shard $i/$shards exit=0" ]]; then
        [[ -f $f ]] && tail -n 20 "$f" >&2
        tail -n 20 "$tmp/slurmd.log" >&2 || true
        echo "shard $i/$shards of job $job_done failed: see $f"
        exit 1
    fi
done
"$bin" merge "$slurm_out" >/dev/null

# --- the same grid locally ----------------------------------------------------------------
say "running the same grid locally"
RAYON_NUM_THREADS=$ncpu "$bin" sweep --seeds "$seeds" --pushes "$pushes" --out "$local_out" \
    >/dev/null
"$bin" merge "$local_out" >/dev/null

# --- compare, without the run-time columns --------------------------------------------------
strip() {
    case $1 in
    *.md) sed -E 's/\|[^|]*\|$/|/' "$1" ;;    # drop the last cell: "run time (s)"
    *.csv) sed -E 's/,[^,]*,[^,]*$//' "$1" ;; # drop run_time_s_mean, run_time_s_std
    esac
}
differs=()
for t in ablation.md ablation.csv; do
    strip "$slurm_out/$t" >"$tmp/slurm-$t"
    strip "$local_out/$t" >"$tmp/local-$t"
    if ! cmp -s "$tmp/slurm-$t" "$tmp/local-$t"; then
        diff "$tmp/local-$t" "$tmp/slurm-$t" >&2 || true
        differs+=("$t")
    fi
done
rows=$(($(wc -l <"$local_out/ablation.csv") - 1))
say "$rows rows per table, total $(($(date +%s) - start)) s"
if ((rows < 1)); then
    echo "differs: the merged tables are empty (no finished run); results in $tmp"
    exit 1
fi
if ((${#differs[@]})); then
    echo "differs: ${differs[*]} (Slurm $slurm_out vs local $local_out, diff above)"
    exit 1
fi
echo identical
