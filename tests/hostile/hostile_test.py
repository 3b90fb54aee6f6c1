#!/usr/bin/python3
"""Hostile input, family by family: each case breaks one thing in a small simulated sequence (or
gives an absurd option) and requires the exit code docs/cli.md gives (0 done, 1 bad input, 2
wrong arguments), a message fragment naming the cause, and for the cases that must not run long
or grow, a bound on wall time. Every case runs in a fresh copy of the sequence.

    hostile_test.py AAVIO_BINARY SCRATCH_DIR

AAVIO_TEST_TIME_SCALE (default 1) multiplies every wall-time bound: a sanitizer build runs the
same work several times slower, and a bound is there to catch a hang, not to time a build.
"""
import base64
import json
import os
import shutil
import subprocess
import sys
import time

AAVIO, SCRATCH = sys.argv[1], sys.argv[2]
TIME_SCALE = float(os.environ.get('AAVIO_TEST_TIME_SCALE', '1'))
BASE = os.path.join(SCRATCH, 'base')
failures = []


def simulate():
    if os.path.exists(os.path.join(BASE, 'sequence.yaml')):
        return
    subprocess.run([AAVIO, 'simulate', '--preset', 'mini', '--duration', '1.5', '--seed', '3',
                    '--format', 'txt', '--out', BASE, '--quiet', '--overwrite'], check=True,
                   stdout=subprocess.DEVNULL)


def fresh(name):
    """A copy of the base sequence to break."""
    path = os.path.join(SCRATCH, name)
    shutil.rmtree(path, ignore_errors=True)
    shutil.copytree(BASE, os.path.join(path, 'seq'))
    return path


def replace(path, old, new):
    with open(path) as f:
        text = f.read()
    assert old in text, (path, old)
    with open(path, 'w') as f:
        f.write(text.replace(old, new))


def link(target, name):
    os.remove(name) if os.path.lexists(name) else None
    os.symlink(target, name)


def shift_stamps(path, seconds):
    lines = []
    for line in open(path):
        fields = line.split()
        if fields and not line.startswith('#'):
            fields[0] = '%.9f' % (float(fields[0]) + seconds)
            line = ' '.join(fields) + '\n'
        lines.append(line)
    open(path, 'w').writelines(lines)


def right_p03(d, value):
    text = open(os.path.join(d, 'seq/calibration/right.yaml')).read()
    start = text.index('projection_matrix')
    data = text.index('data: [', start) + len('data: [')
    fields = text[data:text.index(']', data)].split(',')
    return ','.join(fields[:4]), ','.join(fields[:3] + [' ' + value])


def set_distortion(d, coefficients):
    path = os.path.join(d, 'seq/calibration/left.yaml')
    text = open(path).read()
    start = text.index('distortion_coefficients')
    data = text.index('data: [', start)
    end = text.index(']', data) + 1
    open(path, 'w').write(text[:data] + 'data: ' + coefficients + text[end:])


def thin_imu(d, every):
    path = os.path.join(d, 'seq/imu.txt')
    lines = open(path).readlines()
    header = [l for l in lines if l.startswith('#')]
    samples = [l for l in lines if not l.startswith('#')]
    open(path, 'w').writelines(header + samples[::every] if every < len(samples) else header)


def case(name, argv, code, fragment, setup=None, max_seconds=60, check=None):
    """Runs `aavio ARGV` in a fresh copy (cwd) after `setup(dir)`; {seq} in argv is its sequence."""
    max_seconds *= TIME_SCALE
    d = fresh(name)
    if setup:
        setup(d)
    args = [a.replace('{seq}', os.path.join(d, 'seq')).replace('{dir}', d) for a in argv]
    start = time.monotonic()
    try:
        r = subprocess.run([AAVIO] + args, cwd=d, capture_output=True, text=True,
                           timeout=max_seconds + 30)
    except subprocess.TimeoutExpired:
        failures.append('%s: did not finish within %.0f s' % (name, max_seconds + 30))
        return
    wall = time.monotonic() - start
    out = r.stdout + r.stderr
    problems = []
    if r.returncode != code:
        problems.append('exit code %d, expected %d' % (r.returncode, code))
    if fragment not in out:
        problems.append('no %r in the output' % fragment)
    if wall > max_seconds:
        problems.append('took %.1f s, more than %.0f' % (wall, max_seconds))
    if 'HDF5-DIAG' in out or 'Traceback' in out or 'terminate called' in out:
        problems.append('a raw stack in the output')
    if check and not problems:
        problems += check(d)
    status = 'ok' if not problems else 'FAILED: ' + '; '.join(problems)
    print('%-28s exit %d  %.1f s  %s' % (name, r.returncode, wall, status))
    if problems:
        failures.append('%s: %s\n  output: %s' % (name, '; '.join(problems), out.strip()[-600:]))


def summary(d, run='out'):
    with open(os.path.join(d, run, 'summary.json')) as f:
        return json.load(f)


simulate()
SEQ, LEFT = '{seq}', 'seq/events/left/events.txt'

# ---- Devices, FIFOs, folders, links: refused by their kind before a byte is read.
case('info_dev_zero', ['info', '/dev/zero'], 1, '/dev/zero: is a device, not a file',
     max_seconds=5)
case('config_for_dev_zero', ['config', '--for', '/dev/zero'], 1, 'is a device', max_seconds=5)
case('sensor_dev_zero', ['simulate', '--sensor', '/dev/zero', '--out', 'x'], 1, 'is a device',
     max_seconds=5)
case('eval_dev_urandom', ['eval', '--est', '/dev/urandom', '--gt', 'seq/groundtruth.txt'], 1,
     '/dev/urandom: is a device', max_seconds=5)
case('calib_left_is_device', ['info', 'seq/calibration'], 1,
     'left.yaml: is a device, not a file',
     setup=lambda d: link('/dev/zero', os.path.join(d, 'seq/calibration/left.yaml')),
     max_seconds=5)
case('calib_link_loop', ['run', SEQ, '--out', 'out'], 1, 'a symbolic link that leads to no file',
     setup=lambda d: (link('right.yaml.loop', os.path.join(d, 'seq/calibration/left.yaml')),
                      link('left.yaml', os.path.join(d, 'seq/calibration/right.yaml.loop'))),
     max_seconds=5)
case('gt_is_dev_urandom', ['run', SEQ, '--out', 'out'], 1, 'groundtruth.txt: is a device',
     setup=lambda d: link('/dev/urandom', os.path.join(d, 'seq/groundtruth.txt')), max_seconds=10)
case('imu_is_fifo', ['run', SEQ, '--out', 'out'], 1, 'imu.txt: is a named pipe (FIFO)',
     setup=lambda d: (os.remove(os.path.join(d, 'seq/imu.txt')),
                      os.mkfifo(os.path.join(d, 'seq/imu.txt'))), max_seconds=10)
case('events_are_a_folder', ['run', SEQ, '--out', 'out'], 1, 'is a folder, not a file',
     setup=lambda d: (os.remove(os.path.join(d, LEFT)), os.mkdir(os.path.join(d, LEFT))),
     max_seconds=10)

# ---- Size bounds and binary data where text belongs.
case('huge_calibration', ['info', 'seq/calibration'], 1, 'larger than the 16.0 MB',
     setup=lambda d: open(os.path.join(d, 'seq/calibration/left.yaml'), 'a').write(
         'blob: ' + base64.b64encode(os.urandom(13 << 20)).decode() + '\n'),
     max_seconds=5)
case('binary_trajectory', ['eval', '--est', 'bin.txt', '--gt', 'seq/groundtruth.txt'], 1,
     'holds binary data',
     setup=lambda d: open(os.path.join(d, 'bin.txt'), 'wb').write(b'0 1 2\x00\x01' * 100),
     max_seconds=5)

# ---- Time: streams that do not overlap, gaps of hours.
case('imu_1000s_late', ['run', SEQ, '--out', 'out'], 1, 'the IMU samples span 1000.',
     setup=lambda d: shift_stamps(os.path.join(d, 'seq/imu.txt'), 1000.0), max_seconds=10)
case('right_camera_later', ['run', SEQ, '--out', 'out'], 1, 'they do not overlap',
     setup=lambda d: shift_stamps(os.path.join(d, 'seq/events/right/events.txt'), 100.0),
     max_seconds=15)
case('one_event_3h_later', ['run', SEQ, '--out', 'out'], 0, 'not ticked through',
     setup=lambda d: open(os.path.join(d, LEFT), 'a').write('10801.0 10 10 1\n'),
     max_seconds=30,
     check=lambda d: [] if len(summary(d)['event_gaps']['skipped']) == 1 else
     ['event_gaps.skipped lists %r' % summary(d)['event_gaps']['skipped']])

# ---- Wrong input accepted silently before.
case('duplicate_yaml_key', ['run', SEQ, '--out', 'out'], 1, "key 'name' is given twice",
     setup=lambda d: open(os.path.join(d, 'seq/sequence.yaml'), 'a').write('name: again\n'))
case('one_file_both_cameras', ['run', SEQ, '--out', 'out'], 1,
     'the left and the right camera both read',
     setup=lambda d: replace(os.path.join(d, 'seq/sequence.yaml'), 'events/right/events.txt',
                             'events/left/events.txt'))
case('topic_on_text_file', ['run', SEQ, '--out', 'out'], 1, 'events.left_topic names a topic',
     setup=lambda d: replace(os.path.join(d, 'seq/sequence.yaml'), '  left: events/left',
                             '  left_topic: /cam0/events\n  left: events/left'))
case('polarity_7', ['run', SEQ, '--out', 'out'], 1, 'polarity p = 7',
     setup=lambda d: replace(os.path.join(d, LEFT), '\n', '\n0.0000001 5 5 7\n'))
case('negative_x', ['run', SEQ, '--out', 'out'], 1, 'x and y must be integers from 0 to 65535',
     setup=lambda d: replace(os.path.join(d, LEFT), '\n', '\n0.0000001 -5 5 1\n'))
case('baseline_1e-11', ['run', SEQ, '--out', 'out'], 1, 'outside the 5 mm',
     setup=lambda d: replace(os.path.join(d, 'seq/calibration/right.yaml'),
                             *right_p03(d, '-1e-10')))
case('absurd_distortion', ['run', SEQ, '--out', 'out'], 1, 'no lens distorts that much',
     setup=lambda d: set_distortion(d, '[100, 100, 0, 0]'))

# ---- Legal but useless input: a warning, in the output and in summary.json.
case('imu_at_2hz', ['run', SEQ, '--out', 'out'], 0, 'fewer than one per tick',
     setup=lambda d: thin_imu(d, 100),
     check=lambda d: [] if any('fewer than one per tick' in w for w in summary(d)['warnings'])
     else ['summary.json warnings: %r' % summary(d)['warnings']])
case('imu_empty', ['run', SEQ, '--out', 'out'], 0, 'no IMU samples in the time processed',
     setup=lambda d: thin_imu(d, 10 ** 9))

# ---- Options: absurd values are wrong arguments (exit 2), refused before anything runs.
case('seed_past_64_bits', ['simulate', '--out', 'x', '--seed', '18446744073709551616'], 2,
     'is not a seed', max_seconds=5)
case('fast_outside_sequence', ['simulate', '--preset', 'mini', '--out', 'x', '--fast', '50:1'],
     2, 'after the sequence', max_seconds=5)
case('fast_zero_seconds', ['simulate', '--out', 'x', '--fast', '0.1:0'], 2,
     'SECONDS must be in [0.001, 86400]', max_seconds=5)
case('set_nan', ['run', SEQ, '--out', 'out', '--set', 'mapping.rate_hz=nan'], 2,
     "expected a finite number, got 'nan'", max_seconds=5)
case('set_unknown_key', ['run', SEQ, '--out', 'out', '--set', 'mapping.rte_hz=3'], 2,
     "did you mean 'mapping.rate_hz'", max_seconds=5)
case('set_out_of_range', ['run', SEQ, '--out', 'out', '--set', 'mapping.eta=-1'], 2,
     'mapping.eta = -1 must be >= 0', max_seconds=10)
case('config_file_out_of_range', ['run', SEQ, '--out', 'out', '--config', 'c.yaml'], 1,
     'mapping.eta = -1 must be >= 0',
     setup=lambda d: open(os.path.join(d, 'c.yaml'), 'w').write('mapping:\n  eta: -1\n'),
     max_seconds=10)
case('start_not_a_number', ['run', SEQ, '--out', 'out', '--start', 'abc'], 2,
     "'abc' is not a number", max_seconds=5)

# ---- No silent wrong answer, and summary.json on every exit path.
case('start_past_the_end', ['run', SEQ, '--out', 'out', '--start', '100'], 1,
     'no pose was estimated', max_seconds=10)
case('eval_one_pose', ['eval', '--est', 'one.txt', '--gt', 'seq/groundtruth.txt'], 1,
     'a trajectory score needs at least 10',
     setup=lambda d: open(os.path.join(d, 'one.txt'), 'w').writelines(
         open(os.path.join(d, 'seq/groundtruth.txt')).readlines()[:2]), max_seconds=5)
case('gt_after_the_run', ['run', SEQ, '--out', 'out'], 1, 'summary.json says why',
     setup=lambda d: shift_stamps(os.path.join(d, 'seq/groundtruth.txt'), 100.0),
     check=lambda d: [] if summary(d).get('accuracy_error') else ['no accuracy_error'])
case('eval_run_part_only', ['eval', '--run', 'partial'], 1, 'not found',
     setup=lambda d: (os.mkdir(os.path.join(d, 'partial')),
                      open(os.path.join(d, 'partial/stamped_traj_estimate.txt.part'), 'w')),
     max_seconds=5)
case('report_out_folder', ['report', '--run', 'out', '--out', 'folder'], 0, 'report.html',
     setup=lambda d: (subprocess.run([AAVIO, 'run', os.path.join(d, 'seq'), '--out',
                                      os.path.join(d, 'out'), '--quiet'], check=True,
                                     capture_output=True),
                      os.mkdir(os.path.join(d, 'folder'))))


if failures:
    print('\n%d hostile case(s) failed:\n%s' % (len(failures), '\n'.join(failures)))
    sys.exit(1)
print('all hostile cases behave')
