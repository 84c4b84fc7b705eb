#!/usr/bin/python3
"""A real one-node Slurm cluster on localhost (Debian's munge, slurmctld,
slurmd, slurm-client): `sbatch --wait --array=0-3` runs four shards of a
scene into one folder, `sdgbehave merge` finishes it, and the folder equals
a single run byte for byte. The daemons are stopped by their PIDs.
Exits 77 (reported as skipped by CTest) when not root or when the Slurm
packages are missing; .ci/run installs them."""
import glob
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

from checklib import dataset_hashes

SKIP = 77


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_for(predicate, seconds, what):
    deadline = time.time() + seconds
    while time.time() < deadline:
        if predicate():
            return
        time.sleep(0.2)
    raise RuntimeError(f"timed out waiting for {what}")


def stop(pid_file):
    try:
        pid = int(open(pid_file).read().strip())
        os.kill(pid, signal.SIGTERM)
        for _ in range(50):
            os.kill(pid, 0)
            time.sleep(0.1)
        os.kill(pid, signal.SIGKILL)
    except (OSError, ValueError):
        pass


def main():
    binary, scene = (os.path.abspath(a) for a in sys.argv[1:3])
    if os.geteuid() != 0:
        print("skipped: starting Slurm daemons needs root")
        return SKIP
    missing = [b for b in ("munged", "slurmctld", "slurmd", "sbatch", "sinfo") if not shutil.which(b)]
    if missing or not os.path.exists("/etc/munge/munge.key"):
        print(f"skipped: Slurm packages missing ({', '.join(missing) or 'munge key'}); .ci/run installs them")
        return SKIP
    tmp = tempfile.mkdtemp(prefix="sdg_slurm_")
    os.chmod(tmp, 0o755)
    started_munge = False
    env = {**os.environ, "SLURM_CONF": f"{tmp}/slurm.conf"}
    try:
        # munge: no systemd here, so its run folder and daemon are ours to make.
        os.makedirs("/run/munge", exist_ok=True)
        shutil.chown("/run/munge", "munge", "munge")
        os.chmod("/run/munge", 0o755)
        if subprocess.run(["munge", "-n"], capture_output=True).returncode != 0:
            if subprocess.run(["runuser", "-u", "munge", "--", "munged", "--force"], capture_output=True).returncode:
                print("skipped: munged would not start as the munge user")
                return SKIP
            started_munge = True
            try:
                wait_for(lambda: subprocess.run(["munge", "-n"], capture_output=True).returncode == 0, 10, "munged")
            except RuntimeError:
                print("skipped: munged started but does not answer")
                return SKIP
        for d in ("state", "spool", "out", "logs"):
            os.makedirs(f"{tmp}/{d}")
        cpus = os.cpu_count() or 1
        open(f"{tmp}/slurm.conf", "w").write(f"""ClusterName=sdgtest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort={free_port()}
SlurmdPort={free_port()}
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation={tmp}/state
SlurmdSpoolDir={tmp}/spool
SlurmctldPidFile={tmp}/slurmctld.pid
SlurmdPidFile={tmp}/slurmd.pid
SlurmctldLogFile={tmp}/slurmctld.log
SlurmdLogFile={tmp}/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerParameters=batch_sched_delay=0
ReturnToService=2
MpiDefault=none
NodeName=localhost NodeAddr=127.0.0.1 CPUs={cpus} State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP OverSubscribe=YES
""")
        try:
            subprocess.run(["slurmctld"], env=env, check=True, capture_output=True)
            subprocess.run(["slurmd", "-N", "localhost"], env=env, check=True, capture_output=True)
            wait_for(lambda: subprocess.run(["sinfo", "-h", "-o", "%T"], env=env, capture_output=True,
                                            text=True).stdout.strip() in ("idle", "mixed"), 60, "the node to be idle")
        except (subprocess.CalledProcessError, RuntimeError) as e:
            # The cluster itself would not come up on this machine: that is
            # the environment, not sdgbehave, so the test is skipped, loudly.
            logs = "".join(open(p).read()[-400:] for p in glob.glob(f"{tmp}/*.log"))
            print(f"skipped: the one-node Slurm cluster did not start ({e}); {logs}")
            return SKIP
        script = f"{tmp}/shards.sh"
        open(script, "w").write(f"#!/bin/sh\nexec {binary} run {scene} --out {tmp}/out --threads 1\n")
        os.chmod(script, 0o755)
        job = subprocess.run(["sbatch", "--wait", "--array=0-3", "--cpus-per-task=1", f"--output={tmp}/logs/%A_%a.log",
                              script], env=env, capture_output=True, text=True, timeout=240)
        if job.returncode != 0:
            logs = "".join(open(p).read()[-300:] for p in glob.glob(f"{tmp}/logs/*.log"))
            print(f"sbatch failed ({job.returncode}): {job.stderr.strip()} {logs}")
            return 1
        merged = subprocess.run([binary, "merge", f"{tmp}/out"], capture_output=True, text=True)
        if merged.returncode != 0:
            print(f"merge failed: {merged.stderr.strip()}")
            return 1
        subprocess.run([binary, "run", scene, "--out", f"{tmp}/whole"], check=True, capture_output=True)
        a, b = dataset_hashes(f"{tmp}/out"), dataset_hashes(f"{tmp}/whole")
        if a != b:
            print("the Slurm array's folder differs from a single run: " +
                  ", ".join(sorted(k for k in set(a) | set(b) if a.get(k) != b.get(k)))[:400])
            return 1
        print(f"ok: 4 array tasks, {len(a)} files identical to a single run")
        return 0
    finally:
        stop(f"{tmp}/slurmd.pid")
        stop(f"{tmp}/slurmctld.pid")
        if started_munge:
            stop("/run/munge/munged.pid")
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
