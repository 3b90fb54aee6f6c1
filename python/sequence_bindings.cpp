// open_sequence(path) → Sequence: its time span, rig and ground truth; read() gives every event
// and IMU sample of a time range as numpy arrays, packets() iterates over them in time order.
#include <pybind11/stl.h>

#include <memory>
#include <optional>

#include "aavio/io/calibration.hpp"
#include "aavio/io/sequence.hpp"
#include "bindings.hpp"

namespace aavio::python {
namespace {

struct Sequence {
  io::SequenceDescription description;
  io::LoadedCalibration calibration;
  TimeNs start_ns = 0, end_ns = 0;
};

Sequence OpenSequence(const std::string& path, const std::string& calibration) {
  io::SequenceDescription description = Unwrap(io::DescribeSequence(path, calibration));
  if (description.calibration.empty()) {
    throw py::value_error(path + ": the sequence names no calibration; pass calibration=PATH");
  }
  io::LoadedCalibration loaded = Unwrap(io::LoadCalibration(description.calibration));
  std::unique_ptr<io::SequenceReader> reader =
      Unwrap(io::SequenceReader::Open(description, io::SequenceReaderOptions{}));
  return Sequence{std::move(description), std::move(loaded), reader->start_ns(), reader->end_ns()};
}

py::dict RigDict(const geometry::StereoRig& rig) {
  py::dict d;
  d["width"] = rig.width();
  d["height"] = rig.height();
  d["focal_px"] = rig.focal_px();
  d["cx_left"] = rig.cx_left();
  d["cx_right"] = rig.cx_right();
  d["cy"] = rig.cy();
  d["baseline_m"] = rig.baseline_m();
  return d;
}

/// Packets of [start, end) of a sequence, one at a time.
class PacketIterator {
 public:
  PacketIterator(const Sequence& s, double packet_s, double start_s,
                 std::optional<double> duration_s) {
    if (!(packet_s > 0.0 && packet_s <= 10.0)) {
      throw py::value_error("packet_s must be in (0, 10] seconds");
    }
    if (start_s < 0.0 || (duration_s && *duration_s <= 0.0)) {
      throw py::value_error("start_s must be >= 0 and duration_s > 0");
    }
    io::SequenceReaderOptions options;
    options.packet_ns = SecondsToNs(packet_s);
    reader_ = Unwrap(io::SequenceReader::Open(s.description, options));
    begin_ns_ = reader_->start_ns() + SecondsToNs(start_s);
    end_ns_ = duration_s ? begin_ns_ + SecondsToNs(*duration_s) : reader_->end_ns() + 1;
    if (start_s > 0.0) Check(reader_->Seek(begin_ns_));
  }
  /// The next packet, or nothing at the end.
  std::optional<io::SensorPacket> Next() {
    io::SensorPacket packet;
    bool more = false;
    {
      py::gil_scoped_release release;
      Expected<bool> next = reader_->Next(&packet);
      if (!next) {
        py::gil_scoped_acquire acquire;
        Raise(next.status());
      }
      more = *next;
    }
    if (!more || packet.t_begin_ns >= end_ns_) return std::nullopt;
    if (packet.t_end_ns > end_ns_) {  // the last packet ends with the range
      auto cut = [this](auto& v) {
        while (!v.empty() && v.back().t_ns >= end_ns_)
          v.pop_back();
      };
      cut(packet.left);
      cut(packet.right);
      cut(packet.imu);
      packet.t_end_ns = end_ns_;
    }
    return packet;
  }

 private:
  std::unique_ptr<io::SequenceReader> reader_;
  TimeNs begin_ns_ = 0, end_ns_ = 0;
};

py::dict PacketObject(const io::SensorPacket& p) {
  py::dict d;
  d["t_begin_ns"] = p.t_begin_ns;
  d["t_end_ns"] = p.t_end_ns;
  d["left"] = EventArray(p.left);
  d["right"] = EventArray(p.right);
  d["imu"] = ImuArray(p.imu);
  return d;
}

}  // namespace

void BindSequence(py::module_& m) {
  py::class_<PacketIterator>(m, "PacketIterator")
      .def("__iter__", [](PacketIterator& it) -> PacketIterator& { return it; })
      .def("__next__", [](PacketIterator& it) {
        std::optional<io::SensorPacket> p = it.Next();
        if (!p) throw py::stop_iteration();
        return PacketObject(*p);
      });

  py::class_<Sequence>(m, "Sequence",
                       "A stereo event sequence: a sequence.yaml, a DSEC folder or a bag.")
      .def_readonly("start_ns", &Sequence::start_ns, "earliest stamp of any stream")
      .def_readonly("end_ns", &Sequence::end_ns, "latest stamp of any stream")
      .def_property_readonly("duration_s",
                             [](const Sequence& s) { return NsToSeconds(s.end_ns - s.start_ns); })
      .def_property_readonly("calibration",
                             [](const Sequence& s) { return s.description.calibration; })
      .def_property_readonly(
          "rig", [](const Sequence& s) { return RigDict(s.calibration.rig); },
          "the rectified rig: width, height, focal_px, cx_left, cx_right, cy, "
          "baseline_m")
      .def_property_readonly(
          "ground_truth",
          [](const Sequence& s) -> py::object {
            if (!s.description.gt_trajectory) return py::none();
            return py::str(s.description.gt_trajectory->path);
          },
          "the ground-truth trajectory's file, or None")
      .def_property_readonly("has_imu",
                             [](const Sequence& s) { return s.description.imu.has_value(); })
      .def(
          "packets",
          [](const Sequence& s, double packet_s, double start_s, std::optional<double> duration_s) {
            return PacketIterator(s, packet_s, start_s, duration_s);
          },
          py::arg("packet_s") = 0.01, py::arg("start_s") = 0.0, py::arg("duration_s") = py::none(),
          "Iterates over packets of packet_s seconds of [start_s, start_s + duration_s): dicts "
          "with t_begin_ns, t_end_ns, left, right (EVENT_DTYPE arrays) and imu (IMU_DTYPE).")
      .def(
          "read",
          [](const Sequence& s, double start_s, std::optional<double> duration_s) {
            PacketIterator it(s, 0.05, start_s, duration_s);
            std::vector<events::Event> left, right;
            std::vector<imu::ImuSample> imu;
            while (std::optional<io::SensorPacket> p = it.Next()) {
              left.insert(left.end(), p->left.begin(), p->left.end());
              right.insert(right.end(), p->right.begin(), p->right.end());
              imu.insert(imu.end(), p->imu.begin(), p->imu.end());
            }
            return py::make_tuple(EventArray(left), EventArray(right), ImuArray(imu));
          },
          py::arg("start_s") = 0.0, py::arg("duration_s") = py::none(),
          "(left, right, imu) arrays of [start_s, start_s + duration_s) (default: to the end).");

  m.def("open_sequence", &OpenSequence, py::arg("path"), py::arg("calibration") = "",
        "Opens a sequence.yaml (or a folder holding one), a DSEC sequence folder or a bag; "
        "calibration: an ESVO folder or DSEC cam_to_cam.yaml when the sequence names none.");
}

}  // namespace aavio::python
