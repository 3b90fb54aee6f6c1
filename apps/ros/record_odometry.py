#!/usr/bin/env python3
"""Writes every nav_msgs/Odometry of a topic as an EvSLAM line (t x y z qx qy qz qw vx vy vz: the
pose and the twist's linear part, camera frame), flushed at once: the ROS node test's listener.
  record_odometry.py TOPIC OUT.txt"""
import sys

import rospy
from nav_msgs.msg import Odometry


def main():
    topic, path = sys.argv[1], sys.argv[2]
    out = open(path, "w")

    def on_odometry(m):
        p, q, v = m.pose.pose.position, m.pose.pose.orientation, m.twist.twist.linear
        out.write("%d.%09d %.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n" % (
            m.header.stamp.secs, m.header.stamp.nsecs, p.x, p.y, p.z, q.x, q.y, q.z, q.w,
            v.x, v.y, v.z))
        out.flush()

    rospy.init_node("aavio_test_recorder", disable_signals=False)
    rospy.Subscriber(topic, Odometry, on_odometry, queue_size=10000)
    rospy.spin()
    out.close()


if __name__ == "__main__":
    main()
