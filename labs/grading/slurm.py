"""labs/grade-class --backend slurm: the roster's rows as one Slurm job array, and a one-node
Slurm cluster (munge, slurmctld, slurmd) for tests and a single machine.

Each array task runs `labs/grade-class LAB --task I` on the same roster and output folder: it
fetches and grades row I exactly as the local backend does (its own sandbox, master port,
ROS_HOME and logs) and writes DIR/<isu>/result.json; the submitting process follows the job
with `squeue` and then writes the same gradebook as the local backend.
"""
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time

from grading.common import LABS_DIR

POLL = 2.0


def _run(cmd, timeout=60):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout)
    return r.returncode, r.stdout.decode(errors='replace').strip()


def run_array(g, args, valid):
    """Submit one task per valid row, wait for them, leave the results in g.out."""
    if not valid:
        return
    for tool in ('sbatch', 'squeue'):
        if not shutil.which(tool):
            raise SystemExit('labs/grade-class: error: --backend slurm needs %s (Debian package slurm-client)' % tool)
    d = os.path.join(g.out, 'slurm')
    os.makedirs(d, exist_ok=True)
    cmd = ['/usr/bin/python3', os.path.join(LABS_DIR, 'grade-class'), args.lab, '--roster',
           os.path.abspath(args.roster), '--out', g.out, '--task', '$SLURM_ARRAY_TASK_ID']
    for flag in ('force', 'no_sandbox'):
        if getattr(args, flag):
            cmd.append('--' + flag.replace('_', '-'))
    if args.deadline:
        cmd += ['--deadline', args.deadline]
    if args.timeout:
        cmd += ['--timeout', str(args.timeout)]
    if getattr(args, 'variants', None):
        cmd += ['--variants', os.path.abspath(args.variants)]
    script = os.path.join(d, 'job.sh')
    with open(script, 'w') as f:
        f.write('#!/bin/bash\n'
                '#SBATCH --job-name=grade-%s\n'
                '#SBATCH --output=%s/task-%%a.out\n'
                '#SBATCH --cpus-per-task=1\n'
                '# one task per roster row; each grades its row in its own sandbox\n'
                'exec %s\n' % (args.lab, d, ' '.join(c if c.startswith('$') else "'%s'" % c for c in cmd)))
    n = len(valid)
    rc, out = _run(['sbatch', '--parsable', '--array=0-%d%%%d' % (n - 1, max(1, args.jobs)), script])
    if rc != 0:
        raise SystemExit('labs/grade-class: error: sbatch failed: %s' % out.splitlines()[-1:])
    job = out.split(';')[0].strip()
    print('[grade-class] slurm job array %s: %d tasks, %d at a time' % (job, n, args.jobs), file=sys.stderr, flush=True)
    g.total, g.jobs = n, args.jobs
    t0 = time.time()
    last = None
    while True:
        rc, out = _run(['squeue', '-h', '-j', job, '-o', '%T'])
        states = [s for s in out.split() if s] if rc == 0 else []
        running = sum(1 for s in states if s in ('RUNNING', 'COMPLETING'))
        done = sum(1 for _l, r in valid if _newer(os.path.join(g.out, r['isu'], 'result.json'), t0))
        line = (done, running)
        if line != last:
            print('[grade-class] done %d/%d, running %d, left %d (slurm)'
                  % (done, n, running, max(0, n - done - running)),
                  file=sys.stderr, flush=True)
            last = line
        if rc == 0 and not states:
            break
        time.sleep(POLL)


def _newer(path, t0):
    try:
        return os.path.getmtime(path) >= t0 - 1
    except OSError:
        return False


class OneNodeSlurm:
    """munged + slurmctld + slurmd on this machine, everything under a temp folder; stop()
    ends what start() began (by PID). Sets SLURM_CONF in os.environ while it runs."""

    def __init__(self, root=None, cpus=None):
        self.root = root or tempfile.mkdtemp(prefix='slurm-')
        self.cpus = cpus or os.cpu_count() or 2
        self.procs = []
        self.host = socket.gethostname().split('.')[0]

    def start(self, timeout=90.0):
        r = self.root
        for sub in ('state', 'spool', 'log', 'munge'):
            os.makedirs(os.path.join(r, sub), exist_ok=True)
        os.chmod(os.path.join(r, 'munge'), 0o700)
        key = os.path.join(r, 'munge', 'munge.key')
        with open(key, 'wb') as f:
            f.write(os.urandom(1024))
        os.chmod(key, 0o400)
        sock = os.path.join(r, 'munge', 'munge.socket')
        self.procs.append(subprocess.Popen(
            ['munged', '-F', '--force', '--key-file', key, '--socket', sock,
             '--pid-file', os.path.join(r, 'munge', 'munged.pid'), '--log-file', os.path.join(r, 'log', 'munged.log'),
             '--seed-file', os.path.join(r, 'munge', 'seed')],
            stdout=subprocess.DEVNULL, stderr=open(os.path.join(r, 'log', 'munged.out'), 'wb')))
        port = _free_port()
        conf = os.path.join(r, 'slurm.conf')
        with open(conf, 'w') as f:
            f.write('\n'.join([
                'ClusterName=grading',
                'SlurmctldHost=%s' % self.host,
                'SlurmctldPort=%d' % port,
                'SlurmdPort=%d' % _free_port(),
                'SlurmUser=root',
                'SlurmdUser=root',
                'AuthType=auth/munge',
                'CredType=cred/munge',
                'AuthInfo=socket=%s' % sock,
                'StateSaveLocation=%s' % os.path.join(r, 'state'),
                'SlurmdSpoolDir=%s' % os.path.join(r, 'spool'),
                'SlurmctldPidFile=%s' % os.path.join(r, 'slurmctld.pid'),
                'SlurmdPidFile=%s' % os.path.join(r, 'slurmd.pid'),
                'SlurmctldLogFile=%s' % os.path.join(r, 'log', 'slurmctld.log'),
                'SlurmdLogFile=%s' % os.path.join(r, 'log', 'slurmd.log'),
                'ProctrackType=proctrack/linuxproc',
                'TaskPlugin=task/none',
                'JobAcctGatherType=jobacct_gather/none',
                'SelectType=select/cons_tres',
                'SelectTypeParameters=CR_CPU',
                'ReturnToService=2',
                'MpiDefault=none',
                'NodeName=%s CPUs=%d State=UNKNOWN' % (self.host, self.cpus),
                'PartitionName=grading Nodes=ALL Default=YES MaxTime=INFINITE State=UP',
            ]) + '\n')
        os.environ['SLURM_CONF'] = conf
        env = dict(os.environ)
        self._wait(lambda: os.path.exists(sock), 20,
                   'munged did not start (log: %s)' % os.path.join(r, 'log', 'munged.log'))
        self.procs.append(subprocess.Popen(['slurmctld', '-D', '-f', conf], env=env, stdout=subprocess.DEVNULL,
                                           stderr=open(os.path.join(r, 'log', 'slurmctld.out'), 'wb')))
        self.procs.append(subprocess.Popen(['slurmd', '-D', '-f', conf], env=env, stdout=subprocess.DEVNULL,
                                           stderr=open(os.path.join(r, 'log', 'slurmd.out'), 'wb')))

        def idle():
            rc, out = _run(['sinfo', '-h', '-o', '%T'])
            return rc == 0 and 'idle' in out
        self._wait(idle, timeout, 'the one-node Slurm did not come up (logs in %s)' % os.path.join(r, 'log'))
        return self

    def _wait(self, cond, timeout, why):
        t = time.monotonic()
        while time.monotonic() - t < timeout:
            if cond():
                return
            for p in self.procs:
                if p.poll() is not None:
                    self.stop()
                    raise RuntimeError('%s: %s exited with %s' % (why, p.args[0], p.returncode))
            time.sleep(0.5)
        self.stop()
        raise RuntimeError(why)

    def stop(self):
        for p in reversed(self.procs):
            if p.poll() is None:
                p.terminate()
                try:
                    p.wait(15)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()
        self.procs = []
        os.environ.pop('SLURM_CONF', None)

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()


def _free_port():
    s = socket.socket()
    s.bind(('127.0.0.1', 0))
    p = s.getsockname()[1]
    s.close()
    return p
