// aavio_ros_node: the odometry on live ROS1 topics. Subscribes to the left and right event
// arrays (dvs_msgs, dv_ros_msgs or prophesee_event_msgs EventArray, read as raw bytes: their
// packages are not needed) and sensor_msgs/Imu; publishes nav_msgs/Odometry, the TF world →
// camera, each new local map and the global cloud (PointCloud2) and a depth image (32FC1, m) of
// each new local map. The library does the work (odometry_engine.hpp); this file, compiled as
// C++17 for ROS1's message headers, only wires topics to it. docs/ros.md is the guide.
//
//   aavio_ros_node events_left:=/davis/left/events events_right:=/davis/right/events
//                  imu:=/davis/left/imu _calib_dir:=calib/rpg
// Private parameters: calib_dir (or ESVO2's calibInfoDir), preset, config (YAML file), set
// (list of key=value), real_time (true), max_lag_s (0.05), use_imu (true), world_frame (map),
// camera_frame (dvs_evo), publish_global_cloud_every (10 maps).
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <ros/serialization.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <tf2_ros/transform_broadcaster.h>
#include <topic_tools/shape_shifter.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "odometry_engine.hpp"

namespace aavio::ros_node {
namespace {

ros::Time RosTime(std::int64_t t_ns) {
  ros::Time t;
  t.fromNSec(static_cast<std::uint64_t>(t_ns));
  return t;
}

sensor_msgs::PointCloud2 Cloud(const std::vector<float>& xyz, std::int64_t t_ns,
                               const std::string& frame) {
  sensor_msgs::PointCloud2 cloud;
  cloud.header.stamp = RosTime(t_ns);
  cloud.header.frame_id = frame;
  sensor_msgs::PointCloud2Modifier modifier(cloud);
  modifier.setPointCloud2FieldsByString(1, "xyz");
  modifier.resize(xyz.size() / 3);
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x");
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3, ++x) {
    x[0] = xyz[i], x[1] = xyz[i + 1], x[2] = xyz[i + 2];
  }
  return cloud;
}

class Node {
 public:
  Node(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
    EngineOptions o;
    if (!pnh.getParam("calib_dir", o.calib_dir)) pnh.getParam("calibInfoDir", o.calib_dir);
    pnh.getParam("preset", o.preset);
    pnh.getParam("config", o.config_file);
    pnh.getParam("set", o.overrides);
    pnh.getParam("real_time", o.real_time);
    pnh.getParam("max_lag_s", o.max_lag_s);
    pnh.getParam("use_imu", o.use_imu);
    pnh.param<std::string>("world_frame", world_frame_, "map");
    pnh.param<std::string>("camera_frame", camera_frame_, "dvs_evo");
    pnh.param("publish_global_cloud_every", global_every_, 10);
    std::string error;
    engine_ = OdometryEngine::Create(o, &error);
    if (!engine_) throw std::runtime_error("aavio_ros_node: " + error);
    for (const std::string& w : engine_->warnings())
      ROS_WARN("aavio: %s", w.c_str());
    engine_->on_tick = [this](const TickOutput& tick) { Publish(tick); };

    odometry_pub_ = pnh.advertise<nav_msgs::Odometry>("odometry", 100);
    local_map_pub_ = pnh.advertise<sensor_msgs::PointCloud2>("local_map", 2);
    global_map_pub_ = pnh.advertise<sensor_msgs::PointCloud2>("global_map", 1, true);
    depth_pub_ = pnh.advertise<sensor_msgs::Image>("depth", 2);
    left_sub_ = nh.subscribe<topic_tools::ShapeShifter>(
        "events_left", 1000,
        [this](const topic_tools::ShapeShifter::ConstPtr& m) { OnEvents(0, *m); });
    right_sub_ = nh.subscribe<topic_tools::ShapeShifter>(
        "events_right", 1000,
        [this](const topic_tools::ShapeShifter::ConstPtr& m) { OnEvents(1, *m); });
    if (o.use_imu) {
      imu_sub_ = nh.subscribe<sensor_msgs::Imu>(
          "imu", 5000, [this](const sensor_msgs::Imu::ConstPtr& m) { OnImu(*m); });
    }
    ROS_INFO("aavio: %s; events from %s and %s%s", engine_->Describe().c_str(),
             left_sub_.getTopic().c_str(), right_sub_.getTopic().c_str(),
             o.use_imu ? (", IMU from " + imu_sub_.getTopic()).c_str() : ", no IMU");
  }

  ~Node() {
    // After ros::spin() returns (Ctrl-C, rosnode kill) the ROS log is shut: plain stdout.
    const std::string summary = engine_->Finish();
    if (!summary.empty()) std::printf("aavio: %s\n", summary.c_str());
    std::fflush(stdout);
  }

 private:
  void OnEvents(int camera, const topic_tools::ShapeShifter& message) {
    if (failed_) return;
    std::vector<std::uint8_t> bytes(message.size());
    ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
    message.write(stream);
    std::string error;
    const std::string topic = camera == 0 ? left_sub_.getTopic() : right_sub_.getTopic();
    if (!engine_->PushEventArray(camera, message.getDataType(), message.getMD5Sum(), bytes.data(),
                                 bytes.size(), topic, &error)) {
      Fail(error);
    }
  }

  void OnImu(const sensor_msgs::Imu& m) {
    if (failed_) return;
    ImuReading r;
    r.t_ns = static_cast<std::int64_t>(m.header.stamp.toNSec());
    r.gyro_rad_s = {m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z};
    r.accel_m_s2 = {m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z};
    std::string error;
    if (!engine_->PushImu(r, &error)) Fail(error);
  }

  void Fail(const std::string& error) {
    ROS_ERROR("aavio: %s (the odometry stops)", error.c_str());
    failed_ = true;
  }

  // On the odometry's processing thread (publishers are thread-safe).
  void Publish(const TickOutput& tick) {
    nav_msgs::Odometry odometry;
    odometry.header.stamp = RosTime(tick.t_ns);
    odometry.header.frame_id = world_frame_;
    odometry.child_frame_id = camera_frame_;
    odometry.pose.pose.position.x = tick.position[0];
    odometry.pose.pose.position.y = tick.position[1];
    odometry.pose.pose.position.z = tick.position[2];
    odometry.pose.pose.orientation.x = tick.quaternion[0];
    odometry.pose.pose.orientation.y = tick.quaternion[1];
    odometry.pose.pose.orientation.z = tick.quaternion[2];
    odometry.pose.pose.orientation.w = tick.quaternion[3];
    // In child_frame_id (the camera), as nav_msgs/Odometry defines the twist.
    odometry.twist.twist.linear.x = tick.linear_mps[0];
    odometry.twist.twist.linear.y = tick.linear_mps[1];
    odometry.twist.twist.linear.z = tick.linear_mps[2];
    odometry.twist.twist.angular.x = tick.angular_radps[0];
    odometry.twist.twist.angular.y = tick.angular_radps[1];
    odometry.twist.twist.angular.z = tick.angular_radps[2];
    odometry_pub_.publish(odometry);
    geometry_msgs::TransformStamped tf;
    tf.header = odometry.header;
    tf.child_frame_id = camera_frame_;
    tf.transform.translation.x = tick.position[0];
    tf.transform.translation.y = tick.position[1];
    tf.transform.translation.z = tick.position[2];
    tf.transform.rotation = odometry.pose.pose.orientation;
    tf_.sendTransform(tf);
    if (!tick.has_map) return;
    local_map_pub_.publish(Cloud(tick.map_points_world, tick.map_t_ns, world_frame_));
    sensor_msgs::Image depth;
    depth.header.stamp = RosTime(tick.map_t_ns);
    depth.header.frame_id = camera_frame_;
    depth.width = static_cast<std::uint32_t>(engine_->width());
    depth.height = static_cast<std::uint32_t>(engine_->height());
    depth.encoding = "32FC1";
    depth.step = depth.width * sizeof(float);
    depth.data.resize(tick.map_depth_m.size() * sizeof(float));
    std::memcpy(depth.data.data(), tick.map_depth_m.data(), depth.data.size());
    depth_pub_.publish(depth);
    if (!tick.map_confirmed) return;
    global_.insert(global_.end(), tick.map_points_world.begin(), tick.map_points_world.end());
    if (++maps_ % std::max(1, global_every_) == 0)
      global_map_pub_.publish(Cloud(global_, tick.map_t_ns, world_frame_));
  }

  std::string world_frame_, camera_frame_;
  int global_every_ = 10;
  ros::Publisher odometry_pub_, local_map_pub_, global_map_pub_, depth_pub_;
  ros::Subscriber left_sub_, right_sub_, imu_sub_;
  tf2_ros::TransformBroadcaster tf_;
  std::vector<float> global_;
  int maps_ = 0;
  bool failed_ = false;
  std::unique_ptr<OdometryEngine> engine_;  // last: destroyed first, before the publishers
};

}  // namespace
}  // namespace aavio::ros_node

int main(int argc, char** argv) {
  ros::init(argc, argv, "aavio");
  ros::NodeHandle nh, pnh("~");
  try {
    aavio::ros_node::Node node(nh, pnh);
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("%s", e.what());
    return 1;
  }
  return 0;
}
