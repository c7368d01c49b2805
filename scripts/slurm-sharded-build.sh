#!/usr/bin/env bash
# A dictionary built on a real scheduler: installs a single-node Slurm from Debian packages
# (if missing), starts munge, slurmctld and slurmd on this machine, runs the sharded build as
# a Slurm array job (one `cable-dict build --shard i/n` per task), merges the shards and checks
# that the merged file is byte-identical to a local build of the same setup.
#
# Usage (as root, on a machine you may reconfigure: it writes /etc/slurm/slurm.conf):
#   bash scripts/slurm-sharded-build.sh [SETUP]    (default robots/viper_s850/hand_written/pick_and_place.toml)
# Environment: SHARDS (default 4), DIRECTIONS (default 64), WORK (default target/slurm).
# Exit status: 0 when the merged dictionary equals the local build byte for byte.
set -euo pipefail
cd "$(dirname "$0")/.."
setup="${1:-robots/viper_s850/hand_written/pick_and_place.toml}"
shards="${SHARDS:-4}"
directions="${DIRECTIONS:-64}"
work="$(mkdir -p "${WORK:-target/slurm}" && cd "${WORK:-target/slurm}" && pwd)"
rm -f "$work"/*.cdict "$work"/*.log

if ! command -v slurmctld > /dev/null || ! command -v munged > /dev/null; then
  echo "== installing slurm-wlm and munge (Debian packages)"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge > /dev/null
fi

echo "== munge"
if [ ! -s /etc/munge/munge.key ]; then
  (command -v mungekey > /dev/null && mungekey --create --force) || create-munge-key -f
fi
chown munge:munge /etc/munge/munge.key && chmod 400 /etc/munge/munge.key
mkdir -p /run/munge && chown munge:munge /run/munge
pgrep -x munged > /dev/null || runuser -u munge -- munged --force

echo "== single-node Slurm"
host="$(hostname -s)"
cpus="$(nproc)"
mkdir -p /etc/slurm /var/spool/slurmctld /var/spool/slurmd /var/log/slurm
cat > /etc/slurm/slurm.conf <<EOF
# Written by cable-dict's scripts/slurm-sharded-build.sh: one node, this machine.
ClusterName=cabledict
SlurmctldHost=$host
AuthType=auth/munge
SlurmUser=root
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=build Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
pkill -x slurmctld 2> /dev/null || true
pkill -x slurmd 2> /dev/null || true
sleep 1
slurmctld -i
slurmd
for _ in $(seq 60); do
  state="$(sinfo -h -N -o %t 2> /dev/null | head -n1)"
  case "$state" in idle*|mix*|alloc*) break ;; esac
  sleep 1
done
sinfo

echo "== building cable-dict"
cargo build --release --quiet
bin="$work/cable-dict"
cp target/release/cable-dict "$bin"

echo "== sharded build: a Slurm array job of $shards tasks ($directions directions)"
start=$(date +%s.%N)
sbatch --wait --parsable --job-name=cdict --array="0-$((shards - 1))" --cpus-per-task=1 \
  --output="$work/shard-%a.log" \
  --wrap="\"$bin\" -q build \"$PWD/$setup\" --directions $directions --threads 1 \
          --shard \${SLURM_ARRAY_TASK_ID}/$shards -o \"$work/shard-\${SLURM_ARRAY_TASK_ID}.cdict\""
end=$(date +%s.%N)
echo "array job done in $(echo "$end - $start" | bc) s (wall clock around sbatch --wait)"
for i in $(seq 0 $((shards - 1))); do
  [ -s "$work/shard-$i.cdict" ] || { echo "shard $i missing:"; cat "$work/shard-$i.log"; exit 1; }
done

echo "== merge and compare with a local build"
"$bin" -q merge "$work"/shard-*.cdict -o "$work/merged.cdict"
start=$(date +%s.%N)
"$bin" -q build "$setup" --directions "$directions" -o "$work/local.cdict"
end=$(date +%s.%N)
echo "local build in $(echo "$end - $start" | bc) s"
"$bin" -q verify "$work/merged.cdict"
if cmp "$work/merged.cdict" "$work/local.cdict"; then
  echo "merged dictionary == local build: $(stat -c %s "$work/merged.cdict") bytes, byte for byte"
else
  echo "merged dictionary differs from the local build" >&2
  exit 1
fi
