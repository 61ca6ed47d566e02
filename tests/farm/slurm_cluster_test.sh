#!/usr/bin/env bash
# tests/farm/slurm_cluster_test.sh FOOTPRINT — scripts/farm/slurm-array.sh on a real Slurm: a
# one-node cluster (Debian's slurm-wlm and munge) that the test starts itself, in a temporary
# folder, with its own munge key and socket, its own slurm.conf (localhost, two CPUs) and its own
# ports, every daemon in the foreground and in this script's process group.
#
#   1. The job array and its dependent merge, submitted with the real sbatch exactly as
#      docs/farm.md tells a user, give the whole render's file byte for byte.
#   2. A fault: one array task is requeued (`scontrol requeue`, which kills it) while it renders;
#      Slurm runs it again, the merge still gives the whole render's file byte for byte, and no
#      band, whole or partial, survives the merge.
#
# Every daemon the test started is stopped on exit, whatever happens. Exits 77 (CTest's
# SKIP_RETURN_CODE) where slurm-wlm or munge is not installed, or the test is not root (slurmd
# must be); FOOTPRINT_REQUIRE_SLURM=1 (CI) makes that a failure. A cluster that does not start
# fails the test with the daemons' logs.
set -euo pipefail
footprint=$(realpath "$1")
here=$(dirname "$(realpath "$0")")
script=$here/../../scripts/farm/slurm-array.sh
export PATH=$PATH:/usr/sbin:/sbin

fail() {
    echo "FAIL: $*" >&2
    exit 1
}
skip() {
    if [[ ${FOOTPRINT_REQUIRE_SLURM:-0} != 0 ]]; then fail "FOOTPRINT_REQUIRE_SLURM is set but $*"; fi
    echo "SKIP: $*"
    exit 77
}
for tool in munged mungekey slurmctld slurmd sbatch sinfo squeue scontrol scancel; do
    command -v "$tool" >/dev/null || skip "$tool is not installed (scripts/install-deps.sh installs slurm-wlm and munge)"
done
[[ $(id -u) == 0 ]] || skip "slurmd must run as root"

work=$(mktemp -d /tmp/footprint-slurm.XXXXXX)
cluster=$work/cluster
export SLURM_CONF=$cluster/slurm.conf
pids=() names=()  # the daemons, started in the background of this shell: its process group

# Logs of the daemons and of the jobs, for a failure's message.
logs() {
    local log
    for log in "$cluster"/*.log "$work"/run/slurm-*.out; do
        [[ -s $log ]] || continue
        echo "---- $log (last 30 lines)" >&2
        # munged logs an "Unauthorized credential" line at Info level for each of Slurm's RPCs.
        grep -v 'Info: Unauthorized credential' "$log" | tail -n 30 >&2
    done
}
# The processes of this cluster that are still there: the daemons, and the slurmstepd and job
# processes that slurmd started (they carry this cluster's SLURM_CONF in their environment).
cluster_processes() {
    local pid environ comm
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && echo "$pid"; done
    for pid in /proc/[0-9]*; do
        pid=${pid#/proc/}
        mapfile -d "" environ 2>/dev/null <"/proc/$pid/environ" || continue
        [[ " ${environ[*]} " == *" SLURM_CONF=$SLURM_CONF "* ]] || continue
        read -r comm 2>/dev/null <"/proc/$pid/comm" || continue
        [[ $comm == slurmstepd || " ${environ[*]} " == *" SLURM_JOB_ID="* ]] && echo "$pid"
    done
}
# Cancels every job, then stops every process of the cluster: SIGTERM, SIGKILL after 10 s.
stop_cluster() {
    local status=$? pid deadline left
    trap - EXIT INT TERM
    if ((status != 0 && status != 77)); then logs; fi
    if ((${#pids[@]} == 3)) && kill -0 "${pids[1]}" 2>/dev/null; then  # slurmctld runs
        timeout 10 scancel --partition=debug >/dev/null 2>&1 || true
        deadline=$((SECONDS + 15))
        while [[ -n $(timeout 5 squeue -h -o %A 2>/dev/null) ]] && ((SECONDS < deadline)); do
            sleep 0.2
        done
    fi
    for pid in $(cluster_processes); do kill -TERM "$pid" 2>/dev/null || true; done
    deadline=$((SECONDS + 10))
    while left=$(cluster_processes) && [[ -n $left ]] && ((SECONDS < deadline)); do sleep 0.1; done
    for pid in $left; do kill -KILL "$pid" 2>/dev/null || true; done
    for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
    rm -rf "$work"
    exit "$status"
}
trap stop_cluster EXIT
trap 'exit 143' TERM
trap 'exit 130' INT
chmod 0755 "$work"  # munged wants every folder above its socket searchable by all
mkdir -m 0755 "$cluster" "$cluster/state" "$cluster/spool"

# Waits up to SECONDS for COMMAND to succeed, polling five times a second.
wait_for() {
    local seconds=$1 what=$2 deadline=$((SECONDS + $1))
    shift 2
    until "$@" >/dev/null; do
        ((SECONDS < deadline)) || fail "no $what after ${seconds} s"
        sleep 0.2
    done
}

# start DAEMON ARGUMENT...: in the background (this shell's process group), stderr to DAEMON.log.
start() {
    "$@" 2>>"$cluster/$1.log" &
    pids+=($!) names+=("$1")
}

# munge: a key of its own, a socket of its own.
dd if=/dev/urandom of="$cluster/munge.key" bs=1024 count=1 status=none
chmod 0400 "$cluster/munge.key"
start munged --foreground --force --socket="$cluster/munge.socket" \
    --key-file="$cluster/munge.key" --pid-file="$cluster/munged.pid" \
    --log-file="$cluster/munged.log" --seed-file="$cluster/munged.seed"
wait_for 10 "munge socket" test -S "$cluster/munge.socket"

# Two free TCP ports for slurmctld and slurmd.
free_ports() {
    python3 -c 'import socket
socks = [socket.socket() for _ in range(2)]
for s in socks: s.bind(("127.0.0.1", 0))
print(*(s.getsockname()[1] for s in socks))'
}
read -r ctld_port slurmd_port < <(free_ports)

cat >"$SLURM_CONF" <<EOF
ClusterName=footprint-test
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
# cred_expire: a requeued job waits this long before it runs again (default 120 s).
AuthInfo=socket=$cluster/munge.socket,cred_expire=5
StateSaveLocation=$cluster/state
SlurmdSpoolDir=$cluster/spool
SlurmctldPidFile=$cluster/slurmctld.pid
SlurmdPidFile=$cluster/slurmd.pid
MailProg=/bin/true
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
MpiDefault=none
SwitchType=switch/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
ReturnToService=2
SlurmdParameters=config_overrides
KillWait=2
MinJobAge=3600
InactiveLimit=0
NodeName=localhost NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF

start slurmctld -D -i -f "$SLURM_CONF"
start slurmd -D -N localhost -f "$SLURM_CONF"
node_idle() {
    local i
    for i in "${!pids[@]}"; do
        kill -0 "${pids[i]}" 2>/dev/null || fail "${names[i]} exited before the node came up"
    done
    [[ $(timeout 10 sinfo -h -N -o %T 2>/dev/null) == idle ]]
}
wait_for 60 "idle node in sinfo" node_idle
echo "cluster up after $SECONDS s"
mkdir "$work/run"
cd "$work/run"
export FOOTPRINT=$footprint

# The state of job ID (an array's task: ID_TASK) as scontrol has it, one word per line for an array.
job_states() { timeout 10 scontrol -o show job "$1" | grep -o 'JobState=[A-Z_]*' | cut -d= -f2; }
# Waits for job ID to leave the queue; it must have COMPLETED.
wait_completed() {
    local id=$1 seconds=$2 deadline=$((SECONDS + $2)) states
    while :; do
        states=$(job_states "$id" | sort -u | tr '\n' ' ')
        case $states in
        "COMPLETED ") return 0 ;;
        *PENDING* | *RUNNING* | *CONFIGURING* | *COMPLETING* | *REQUEUE* | "") ;;
        *) fail "job $id ended $states: $(timeout 10 scontrol -o show job "$id")" ;;
        esac
        ((SECONDS < deadline)) || fail "job $id not completed after $seconds s: $states"
        sleep 0.2
    done
}

# Bands of a few seconds each (one thread each), so that the fault below finds one rendering. The
# whole render's CPU time (all threads) sizes the moment of the fault.
look=(--size 128 --filter reference --spp 2048)
TIMEFORMAT='%U %S'
whole_cpu=$({ time "$footprint" render water "${look[@]}" --quiet -o whole.png; } 2>&1)
options=("${look[@]}" --threads 1)

# 1. Three bands by the job array, merged by the dependent job: the whole render's file.
mapfile -t ids < <("$script" --tiles 3 -o split.png water -- "${options[@]}")
((${#ids[@]} == 2)) || fail "expected two job ids, got: ${ids[*]}"
timeout 10 scontrol -o show job "${ids[1]}" | grep -q "Dependency=afterok:${ids[0]}_\*" ||
    fail "the merge does not wait for the array: $(timeout 10 scontrol -o show job "${ids[1]}")"
wait_completed "${ids[0]}" 120
wait_completed "${ids[1]}" 60
cmp whole.png split.png || fail "the merged bands differ from the whole render"
[[ ! -e split.png.tiles ]] || fail "the merge job left its bands behind"
echo "job array $(tr '\n' ' ' <<<"${ids[*]}")merged: the whole render's file ($SECONDS s)"

# 2. The fault: band 2 is requeued while it renders. `scontrol requeue` kills the task's processes
# and queues the task again; the merge waits for its second run.
# The pid of the footprint process of task TASK of array ARRAY, if it runs.
task_process() {
    local pid
    for pid in $(pgrep -x footprint); do
        tr '\0' '\n' <"/proc/$pid/environ" 2>/dev/null |
            grep -cxE "SLURM_ARRAY_JOB_ID=$1|SLURM_ARRAY_TASK_ID=$2" | grep -qx 2 &&
            { echo "$pid"; return 0; }
    done
    return 1
}
# CPU time (user + system) process PID has used, in clock ticks; 0 once it has ended.
cpu_ticks() {
    local stat
    stat=$(cut -d')' -f2- "/proc/$1/stat" 2>/dev/null) || { echo 0; return; }
    read -r -a stat <<<"$stat"
    echo $((stat[11] + stat[12]))
}
alive() {
    local stat
    stat=$(cut -d')' -f2- "/proc/$1/stat" 2>/dev/null) && [[ ${stat:1:1} != Z ]]
}
mapfile -t ids < <("$script" --tiles 3 -o fault.png water -- "${options[@]}")
((${#ids[@]} == 2)) || fail "expected two job ids, got: ${ids[*]}"
array=${ids[0]}
wait_for 60 "footprint process for task ${array}_2" task_process "$array" 2
victim=$(task_process "$array" 2)
# A band costs about a third of the whole render: the fault comes at a fifth of the whole render's
# CPU time, past footprint's start (about a CPU second here) and well before the band's end.
read -r user system <<<"$whole_cpu"
threshold=$(awk -v u="$user" -v s="$system" -v hz="$(getconf CLK_TCK)" 'BEGIN { print int((u + s) * hz / 5) }')
rendering() {
    alive "$victim" || fail "task ${array}_2 ended before the fault (faster than a fifth of $whole_cpu s?)"
    (($(cpu_ticks "$victim") >= threshold))
}
wait_for 60 "CPU time in task ${array}_2" rendering
[[ ! -e fault.png.tiles/tile-2.exr ]] || fail "band 2 was written before the fault"
timeout 10 scontrol requeue "${array}_2" || fail "scontrol requeue ${array}_2 failed"
gone() { ! alive "$victim"; }
wait_for 30 "end of the requeued task's process $victim" gone
[[ ! -e fault.png.tiles/tile-2.exr ]] || fail "the killed task wrote band 2"
echo "task ${array}_2 requeued while rendering ($SECONDS s)"
wait_completed "$array" 180
wait_completed "${ids[1]}" 60
timeout 10 scontrol -o show job "${array}_2" | grep -q 'Restarts=1 ' ||
    fail "task ${array}_2 did not run twice: $(timeout 10 scontrol -o show job "${array}_2")"
cmp whole.png fault.png || fail "after the fault, the merged bands differ from the whole render"
[[ ! -e fault.png.tiles ]] || fail "the merge job left its bands behind"
leftovers=$(find "$work/run" -name '*.exr' -o -name '*.tmp-*')
[[ -z $leftovers ]] || fail "partial or stray bands survived: $leftovers"
echo "requeued band merged: the whole render's file ($SECONDS s)"
