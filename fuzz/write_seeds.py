#!/usr/bin/python3
"""Writes the seed corpus of the fuzz targets (fuzz/corpus/<target>/) from the test fixtures.

Run after the unit tests (their writers leave small files under BUILD/test_tmp):
    fuzz/write_seeds.py BUILD_DIR
Files written by the C++ tests' writers (AEDAT4, Prophesee RAW, ROS 2 bags, calibrations,
configs, sequence.yaml) are copied; bags (none, bz2, lz4) and DSEC HDF5 files are written here
with the fixture writers' libraries (rosbag, h5py) but a handful of events, to keep seeds small.
"""
import glob
import os
import shutil
import subprocess
import sys

import h5py
import hdf5plugin
import numpy as np
import genpy.dynamic
import rosbag
import rospy

BUILD = sys.argv[1]
CORPUS = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'corpus')


def out(target, name):
    d = os.path.join(CORPUS, target)
    os.makedirs(d, exist_ok=True)
    return os.path.join(d, name)


def newest(pattern):
    hits = sorted(glob.glob(os.path.join(BUILD, 'test_tmp', pattern)), key=os.path.getmtime)
    if not hits:
        sys.exit('write_seeds.py: no ' + pattern + ' under ' + BUILD + '/test_tmp: run the tests first')
    return hits[-1]


def copy(target, pattern, name):
    shutil.copyfile(newest(pattern), out(target, name))


# C++ test writers' files.
copy('aedat4', 'Aedat4.EventsAndImuOfAnLz4RecordingWithFramesSkipped*/davis.aedat4', 'lz4.aedat4')
copy('aedat4', 'Aedat4.ZstandardAndUncompressedFilesAndSeek*/c3.aedat4', 'zstd.aedat4')
copy('aedat4', 'Aedat4.ZstandardAndUncompressedFilesAndSeek*/c0.aedat4', 'plain.aedat4')
copy('prophesee_raw', 'PropheseeRaw.Evt2EventsWithTheirTimeAndGeometryFromThePlugin*/evt2.raw', 'evt2.raw')
copy('prophesee_raw', 'PropheseeRaw.Evt3VectorsWrapAndSteppedBackTimeLow*/evt3.raw', 'evt3.raw')
copy('prophesee_raw', 'PropheseeRaw.SeekRestartsAtTheTime*/seek.raw', 'seek.raw')
copy('ros2_bag', 'Ros2Bag.McapBagsOfLibcaerCmpPacketsInChunksOrAlone*/caer_cmp.mcap', 'caer_cmp.mcap')
copy('ros2_bag', 'Ros2Bag.Evt3PacketsKeepTheDecoderStateAcrossMessages*/evt3.db3', 'evt3.db3')
copy('calibration', 'DsecCalibrationTest.SequenceFolderAndCalibrationFolderAreFound*/calibration/cam_to_cam.yaml',
     'cam_to_cam.yaml')
for test, name in (('EsvoCalibration.LoadsTheRpgPair', 'rpg'),
                   ('EsvoCalibration.DerivesTheExtrinsicFromNineNumbersWithAWarning', 'nine_numbers')):
    left = open(newest(test + '*/left.yaml')).read()
    right = open(newest(test + '*/right.yaml')).read()
    open(out('calibration', name + '.yaml'), 'w').write(left + '\n--8<--\n' + right)
copy('config', 'ConfigYaml.WrittenConfigReadsBackIdentically*/config.yaml', 'config.yaml')
copy('config', 'Sequence.ReadsASequenceYamlWithRelativePaths*/sequence.yaml', 'sequence.yaml')
open(out('config', 'set.txt'), 'w').write(
    'mapping.eta=0.1\ntracking.rate_hz=100\nimu.T_body_cam=[0.1, 0, 0]\nsampling.mode=adaptive\n')

# Text readers.
open(out('text', 'events.txt'), 'w').write(
    '0.000100 10 20 1\n0.000200 11 20 0\n0.000250\t12\t21\t1\n# comment\n\n0.0003,13,22,0\n')
open(out('text', 'imu_ecd.txt'), 'w').write(
    '0.001 0.1 9.8 0.2 0.01 0.02 0.03\n0.002 0.1 9.8 0.2 0.01 0.02 0.03\n')
open(out('text', 'imu_tumvie.txt'), 'w').write(
    '# timestamp[us] gx gy gz ax ay az\n1000 0.01 0.02 0.03 0.1 9.8 0.2\n2000 0.01 0.02 0.03 0.1 9.8 0.2\n')
open(out('text', 'trajectory.txt'), 'w').write(
    '# t x y z qx qy qz qw\n1.0 0 0 0 0 0 0 1\n1.1 0.1 0 0 0 0 0.0499792 0.9987503\n')

# Decompression: the mode byte (bit 0: zstd, bit 1: size stated) and a frame.
payload = bytes(range(256)) * 4
for mode, tool in ((0, 'lz4'), (1, 'zstd')):
    frame = subprocess.run([tool, '-c', '-q'], input=payload, capture_output=True, check=True).stdout
    open(out('decompression', tool + '.bin'), 'wb').write(bytes([mode]) + frame)

# DSEC HDF5: 8 events, blosc-compressed and plain.
t = np.array([0, 100, 250, 300, 1200, 1500, 2100, 2500], dtype='<u4')
x = np.array([1, 5, 639, 0, 20, 21, 22, 300], dtype='<u2')
y = np.array([2, 6, 479, 0, 40, 41, 42, 200], dtype='<u2')
p = np.array([1, 0, 1, 0, 1, 1, 0, 0], dtype='u1')
for name, kw in (('blosc', dict(chunks=True, **hdf5plugin.Blosc(cname='zstd', clevel=1,
                                                                  shuffle=hdf5plugin.Blosc.BITSHUFFLE))),
                 ('plain', {})):
    with h5py.File(out('dsec_h5', name + '.h5'), 'w') as f:
        for key, v in (('t', t), ('x', x), ('y', y), ('p', p)):
            f.create_dataset('events/' + key, data=v, **kw)
        f.create_dataset('ms_to_idx', data=np.array([0, 4, 6], dtype='<u8'))
        f.create_dataset('t_offset', data=np.int64(36470123457))
with h5py.File(out('dsec_h5', 'rectify_map.h5'), 'w') as f:
    f.create_dataset('rectify_map', data=np.zeros((4, 4, 2), dtype='<f4'))

# ROS1 bags: two event packets, three IMU samples, two poses, per chunk compression.
EV = ('Header header\nuint32 height\nuint32 width\nEvent[] events\n' + '=' * 80 +
      '\nMSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n' + '=' * 80 +
      '\nMSG: dvs_msgs/Event\nuint16 x\nuint16 y\ntime ts\nbool polarity\n')
IMU = ('Header header\ngeometry_msgs/Quaternion orientation\nfloat64[9] orientation_covariance\n'
       'geometry_msgs/Vector3 angular_velocity\nfloat64[9] angular_velocity_covariance\n'
       'geometry_msgs/Vector3 linear_acceleration\nfloat64[9] linear_acceleration_covariance\n' +
       '=' * 80 + '\nMSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n' + '=' * 80 +
       '\nMSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n' + '=' * 80 +
       '\nMSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z\n')
POSE = ('Header header\ngeometry_msgs/Pose pose\n' + '=' * 80 +
        '\nMSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n' + '=' * 80 +
        '\nMSG: geometry_msgs/Pose\ngeometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n' +
        '=' * 80 + '\nMSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n' + '=' * 80 +
        '\nMSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n')
dvs = genpy.dynamic.generate_dynamic('dvs_msgs/EventArray', EV)
imu_cls = genpy.dynamic.generate_dynamic('sensor_msgs/Imu', IMU)['sensor_msgs/Imu']
pose_cls = genpy.dynamic.generate_dynamic('geometry_msgs/PoseStamped', POSE)['geometry_msgs/PoseStamped']
for compression in ('none', 'bz2', 'lz4'):
    with rosbag.Bag(out('rosbag', compression + '.bag'), 'w', compression=compression) as bag:
        for k in range(2):
            for topic in ('/davis/left/events', '/davis/right/events'):
                m = dvs['dvs_msgs/EventArray']()
                m.height, m.width = 180, 240
                m.header.stamp = rospy.Time(100, 2000 + 1000 * k)
                for i in range(3):
                    e = dvs['dvs_msgs/Event']()
                    e.x, e.y, e.polarity = 10 + i, 20 + k, bool(i % 2)
                    e.ts = rospy.Time(100, 1000 * k + 300 * i)
                    m.events.append(e)
                bag.write(topic, m, m.header.stamp)
        for k in range(3):
            m = imu_cls()
            m.header.stamp = rospy.Time(100, 1000 * k)
            m.linear_acceleration.y = 9.81
            bag.write('/davis/left/imu', m, m.header.stamp)
        for k in range(2):
            m = pose_cls()
            m.header.stamp = rospy.Time(100, 1500 * k)
            m.pose.orientation.w = 1.0
            bag.write('/gt/pose', m, m.header.stamp)
print('write_seeds.py: wrote', CORPUS)
