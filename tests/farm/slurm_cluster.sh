# A single-node Slurm for tests, from Debian's packages (munge, slurmctld, slurmd), in a folder of its
# own: a generated munge key and socket, a slurm.conf on localhost with free ports and its own state
# and spool folders, no cgroups (proctrack/linuxproc, task/none). Run as root (slurmd starts jobs as
# their users). Sourced by the tests; `slurm_cluster_start DIR` exports SLURM_CONF for sbatch and
# friends, `slurm_cluster_stop` cancels what is left and stops the daemons it started (by their ids).

SLURM_CLUSTER_PIDS=()

# A TCP port nobody listens on (ports in /proc/net/tcp* are hexadecimal).
slurm_free_port() {
  local port
  for _ in $(seq 100); do
    port=$((20000 + RANDOM % 30000))
    if ! grep -qi ":$(printf '%04X' "$port") " /proc/net/tcp /proc/net/tcp6 2>/dev/null &&
      ! grep -qi ":$(printf '%04X' $((port + 1))) " /proc/net/tcp /proc/net/tcp6 2>/dev/null; then
      echo "$port"
      return 0
    fi
  done
  return 1
}

slurm_cluster_start() {
  local dir=$1 node cpus ctld_port slurmd_port
  node=$(hostname -s)
  cpus=$(nproc)
  ctld_port=$(slurm_free_port)
  slurmd_port=$((ctld_port + 1))
  mkdir -p "$dir/state" "$dir/spool"
  chmod 700 "$dir"
  head -c 1024 /dev/urandom >"$dir/munge.key"
  chmod 400 "$dir/munge.key"
  # --force: munged refuses to run as root, or with its files in /tmp, without it.
  munged --foreground --force --key-file="$dir/munge.key" --socket="$dir/munge.sock" --pid-file="$dir/munged.pid" \
    --log-file="$dir/munged.log" --seed-file="$dir/munged.seed" &
  SLURM_CLUSTER_PIDS+=($!)
  cat >"$dir/slurm.conf" <<CONF
ClusterName=welkintest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge.sock
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
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
MailProg=/bin/true
MinJobAge=600
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF=$dir/slurm.conf
  for _ in $(seq 50); do [ -S "$dir/munge.sock" ] && break; sleep 0.1; done
  slurmctld -D -c -f "$SLURM_CONF" >"$dir/slurmctld.out" 2>&1 &
  SLURM_CLUSTER_PIDS+=($!)
  slurmd -D -f "$SLURM_CONF" -N "$node" >"$dir/slurmd.out" 2>&1 &
  SLURM_CLUSTER_PIDS+=($!)
  # Up when the node takes jobs.
  for _ in $(seq 300); do
    if sinfo -h -o '%t' 2>/dev/null | grep -qE '^(idle|mix|alloc)'; then return 0; fi
    sleep 0.1
  done
  echo "the test cluster did not come up; its logs:" >&2
  tail -n 20 "$dir"/*.log "$dir"/*.out >&2
  return 1
}

# Waits (at most `limit` seconds) until no job of ours is pending or running.
slurm_wait_idle() {
  local limit=$1 start=$SECONDS
  while [ -n "$(squeue -h -o %i 2>/dev/null)" ]; do
    if ((SECONDS - start > limit)); then
      echo "jobs still queued after ${limit} s:" >&2
      squeue >&2
      return 1
    fi
    sleep 0.5
  done
}

slurm_cluster_stop() {
  if [ -n "${SLURM_CONF:-}" ]; then
    scancel --full --user=root 2>/dev/null || true
    slurm_wait_idle 30 || true
  fi
  local pid
  for pid in "${SLURM_CLUSTER_PIDS[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${SLURM_CLUSTER_PIDS[@]}"; do wait "$pid" 2>/dev/null || true; done
  SLURM_CLUSTER_PIDS=()
}
