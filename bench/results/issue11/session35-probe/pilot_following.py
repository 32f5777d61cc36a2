#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
"""The later steps' operator assembled at fair()'s own first step instead of two lazy passes: the
automatic choice, then one step at it (the CLI, --steps 1), whose positions a build with
throwaway.patch reads from FAIRING_PILOT_FILE (raw doubles) as the copy the later operator is
assembled at, then the choice again, ITER times. Prints time step:auto / oracle per round.
  BIN=BENCH/bin CLI=.../implicit-fairing [PILOT_TS=t] pilot_following.py NOISY CLEAN TRUTH OP
      STEPS ORACLE_RMS [ITER]
PILOT_TS: the first pilot at this time step instead of the first choice."""
import json, os, struct, subprocess, sys, tempfile

noisy, clean, truth, op, steps, oracle = sys.argv[1:7]
rounds = int(sys.argv[7]) if len(sys.argv) > 7 else 2
oracle = float(oracle)
work = tempfile.mkdtemp()


def automatic(env):
    e = dict(os.environ)
    e.update(env)
    lines = subprocess.run([os.path.join(os.environ['BIN'], 'fairing-denoise-tool'), 'sweep',
                            noisy, clean, truth, op, '2', steps, '1', '--auto', '--ts', '1'],
                           capture_output=True, text=True, env=e).stdout.splitlines()
    a = [json.loads(l) for l in lines if '"auto"' in l][0]
    return a['time_step'], a['rms']


def pilot(ts, path):
    off = os.path.join(work, 'pilot.off')
    subprocess.run([os.environ['CLI'], noisy, off, '--operator', op, '--order', '2', '--steps',
                    '1', '--time-step', repr(ts)], check=True, capture_output=True)
    lines = [l for l in open(off).read().split('\n') if l.strip() and not l.startswith('#')]
    count = int(lines[1].split()[0])
    values = [float(t) for l in lines[2:2 + count] for t in l.split()[:3]]
    open(path, 'wb').write(struct.pack('<%dd' % len(values), *values))


ts, rms = automatic({})
out = ['%.4g:%.3f' % (ts, rms / oracle)]
if os.environ.get('PILOT_TS'):
    ts = float(os.environ['PILOT_TS'])
for k in range(rounds):
    path = os.path.join(work, 'pilot%d.bin' % k)
    pilot(ts, path)
    ts, rms = automatic({'FAIRING_PILOT_FILE': path})
    out.append('%.4g:%.3f' % (ts, rms / oracle))
print(os.environ.get('LABEL', ''), op, steps, ' '.join(out), flush=True)
