#include "aavio/io/formats/dsec_h5/dsec_h5_reader.hpp"

#include <algorithm>
#include <array>
#include <filesystem>
#include <limits>
#include <type_traits>

#include "aavio/common/format.hpp"
#include "aavio/common/vector_clones.hpp"
#include "aavio/io/decoded_stream_impl.hpp"
#include "aavio/io/file_checks.hpp"
#include "aavio/io/formats/dsec_h5/hdf5_util.hpp"

namespace aavio::io {

namespace {

const char* kFields[4] = {"/events/x", "/events/y", "/events/p", "/events/t"};

}  // namespace

struct DsecH5Decoder {
  std::string path;
  StreamOptions options;
  StreamInfo info;
  h5::Handle file;
  std::array<h5::Handle, 4> datasets;  // x, y, p, t
  std::int64_t t_offset_us = 0;
  std::vector<std::uint64_t> ms_to_idx;
  std::uint64_t count = 0;
  std::uint64_t next_index = 0;  // next event to read from the file
  ReorderBuffer<events::Event> reorder{0};
  // Each column is read in the file's own integer type (HDF5's conversions cost more than the
  // decompression) and widened to int64 here, where every value but uint64's upper half is
  // exact: a signed file's -1 or a wrong column's 70000 shows as it is.
  std::array<h5::Handle, 4> file_types;  // native, as the file stores x, y, p, t
  std::vector<unsigned char> raw;
  std::vector<std::int64_t> xs, ys, ps, ts;
  std::vector<events::Event> block;  // the block's events before the reorder buffer
  // DSEC's own layout (x, y uint16, p uint8, t uint32): read as it is and converted in one pass.
  bool dsec_layout = false;
  std::vector<std::uint16_t> raw_x, raw_y;
  std::vector<std::uint8_t> raw_p;
  std::vector<std::uint32_t> raw_t;

  Status ReadRange(std::uint64_t begin, std::uint64_t n);
  Status ReadBlock();
  /// The block's events into `block` from the DSEC layout; false if one is out of range.
  Expected<bool> ReadDsecLayout(std::uint64_t n, std::int64_t max_x, std::int64_t max_y);
  /// The same from any integer layout, through the int64 columns.
  Expected<bool> ReadAnyLayout(std::uint64_t n, std::int64_t max_x, std::int64_t max_y);
  /// The error of the first bad event among the block's `n` (ReadBlock found one).
  Status DescribeBadEvent(std::uint64_t n) const;
  Expected<std::int64_t> ReadT(std::uint64_t index);

  Status ReadUntil(TimeNs t_end_ns, std::vector<events::Event>* out);
  Status Seek(TimeNs t_ns);
  bool AtEnd() const { return next_index >= count && reorder.size() == 0; }
};

template class DecodedStream<events::Event, DsecH5Decoder>;

namespace {

Status ReadSlab(hid_t dataset, hid_t mem_type, std::uint64_t begin, std::uint64_t n, void* buffer,
                const std::string& path, const char* name) {
  h5::Handle space(H5Dget_space(dataset), H5Sclose);
  const hsize_t start = begin;
  const hsize_t count = n;
  h5::Handle mem(H5Screate_simple(1, &count, nullptr), H5Sclose);
  if (!space.valid() || !mem.valid() ||
      H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, &start, nullptr, &count, nullptr) < 0 ||
      H5Dread(dataset, mem_type, mem.get(), space.get(), H5P_DEFAULT, buffer) < 0) {
    const std::string detail = h5::TakeErrorMessage();
    return IoError(path + ": reading " + name + " events [" + std::to_string(begin) + ", " +
                   std::to_string(begin + n) + ") failed; the file is truncated or corrupt" +
                   (detail.empty() ? "" : " (HDF5: " + detail + ")"));
  }
  return Status::Ok();
}

template <typename T>
void WidenFrom(const unsigned char* raw, std::size_t n, std::int64_t* out) {
  const T* values = reinterpret_cast<const T*>(raw);
  for (std::size_t i = 0; i < n; ++i) {
    if constexpr (std::is_same_v<T, std::uint64_t>) {
      out[i] = static_cast<std::int64_t>(
          std::min<std::uint64_t>(values[i], std::numeric_limits<std::int64_t>::max()));
    } else {
      out[i] = static_cast<std::int64_t>(values[i]);
    }
  }
}

// The values of native integer `type` in `raw` as int64 (the open checked its size).
void Widen(hid_t type, const unsigned char* raw, std::size_t n, std::int64_t* out) {
  const bool is_signed = H5Tget_sign(type) == H5T_SGN_2;
  switch (H5Tget_size(type)) {
    case 1:
      return is_signed ? WidenFrom<std::int8_t>(raw, n, out) : WidenFrom<std::uint8_t>(raw, n, out);
    case 2:
      return is_signed ? WidenFrom<std::int16_t>(raw, n, out)
                       : WidenFrom<std::uint16_t>(raw, n, out);
    case 4:
      return is_signed ? WidenFrom<std::int32_t>(raw, n, out)
                       : WidenFrom<std::uint32_t>(raw, n, out);
    default:
      return is_signed ? WidenFrom<std::int64_t>(raw, n, out)
                       : WidenFrom<std::uint64_t>(raw, n, out);
  }
}

struct ColumnRange {
  std::int64_t min = 0, max = 0;
};

// The smallest and largest of n ≥ 1 values, in a loop the compiler vectorises.
AAVIO_AVX2_CLONES ColumnRange RangeOf(const std::int64_t* values, std::size_t n) {
  std::int64_t lo = values[0], hi = values[0];
  for (std::size_t i = 1; i < n; ++i) {
    lo = std::min(lo, values[i]);
    hi = std::max(hi, values[i]);
  }
  return {lo, hi};
}

struct DsecRanges {
  std::uint16_t x_max = 0, y_max = 0;
  std::uint8_t p_max = 0;
  std::uint32_t t_min = 0, t_max = 0;
};

// Events from DSEC's columns (n ≥ 1), with the extremes that decide whether all are valid.
AAVIO_AVX2_CLONES DsecRanges ConvertDsec(const std::uint16_t* x, const std::uint16_t* y,
                                         const std::uint8_t* p, const std::uint32_t* t,
                                         std::size_t n, std::int64_t t_offset_us,
                                         events::Event* out) {
  DsecRanges r{x[0], y[0], p[0], t[0], t[0]};
  for (std::size_t i = 0; i < n; ++i) {
    r.x_max = std::max(r.x_max, x[i]);
    r.y_max = std::max(r.y_max, y[i]);
    r.p_max = std::max(r.p_max, p[i]);
    r.t_min = std::min(r.t_min, t[i]);
    r.t_max = std::max(r.t_max, t[i]);
    // Wraps only where the range check below fails (then the block is refused).
    const std::uint64_t t_ns =
        (t[i] + static_cast<std::uint64_t>(t_offset_us)) * static_cast<std::uint64_t>(kNsPerUs);
    out[i] = {static_cast<TimeNs>(t_ns), x[i], y[i], static_cast<std::uint8_t>(p[i] > 0 ? 1 : 0)};
  }
  return r;
}

}  // namespace

Status DsecH5Decoder::ReadRange(std::uint64_t begin, std::uint64_t n) {
  h5::SilenceErrorPrinting();  // HDF5's printing is per thread: this may be a reader's thread
  const std::array<std::vector<std::int64_t>*, 4> columns = {&xs, &ys, &ps, &ts};
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const hid_t type = file_types[c].get();
    raw.resize(n * H5Tget_size(type));
    AAVIO_RETURN_IF_ERROR(
        ReadSlab(datasets[c].get(), type, begin, n, raw.data(), path, kFields[c]));
    columns[c]->resize(n);
    Widen(type, raw.data(), n, columns[c]->data());
  }
  return Status::Ok();
}

Status DsecH5Decoder::DescribeBadEvent(std::uint64_t n) const {
  // HDF5 would clamp a negative x to 0 when reading it as uint16; a polarity other than 0/1
  // (or -1/1) is a wrong column or a corrupt file.
  for (std::uint64_t i = 0; i < n; ++i) {
    if (xs[i] < 0 || ys[i] < 0 || xs[i] > 65535 || ys[i] > 65535 || ps[i] < -1 || ps[i] > 1) {
      return InvalidArgument(path + ": event " + std::to_string(next_index + i) +
                             " has x = " + std::to_string(xs[i]) +
                             ", y = " + std::to_string(ys[i]) + ", p = " + std::to_string(ps[i]) +
                             ": x and y must be pixel columns and rows (0 to 65535), p 0 or 1; a "
                             "corrupt file, or a converter that wrote the wrong column?");
    }
  }
  const int width = options.width;
  const int height = options.height;
  if (width > 0) {
    for (std::uint64_t i = 0; i < n; ++i) {
      if (xs[i] >= width || ys[i] >= height) {
        return InvalidArgument(
            path + ": event " + std::to_string(next_index + i) + " at (" + std::to_string(xs[i]) +
            ", " + std::to_string(ys[i]) + ") is outside the " + std::to_string(width) + "x" +
            std::to_string(height) + " sensor; does the calibration belong to this recording?");
      }
    }
  }
  for (std::uint64_t i = 0; i < n; ++i) {
    TimeNs t_ns = 0;
    if (!MicrosecondsToNs(ts[i], t_offset_us, &t_ns)) {
      return ParseError(path + ": event " + std::to_string(next_index + i) + " at t = " +
                        std::to_string(ts[i]) + " µs (+ t_offset " + std::to_string(t_offset_us) +
                        ") is beyond what nanoseconds hold (292 years): a corrupt file");
    }
  }
  return InvalidArgument(path + ": a corrupt block of events");  // not reached
}

Expected<bool> DsecH5Decoder::ReadDsecLayout(std::uint64_t n, std::int64_t max_x,
                                             std::int64_t max_y) {
  h5::SilenceErrorPrinting();
  raw_x.resize(n), raw_y.resize(n), raw_p.resize(n), raw_t.resize(n);
  void* buffers[4] = {raw_x.data(), raw_y.data(), raw_p.data(), raw_t.data()};
  for (std::size_t c = 0; c < 4; ++c) {
    AAVIO_RETURN_IF_ERROR(ReadSlab(datasets[c].get(), file_types[c].get(), next_index, n,
                                   buffers[c], path, kFields[c]));
  }
  block.resize(n);
  const DsecRanges r = ConvertDsec(raw_x.data(), raw_y.data(), raw_p.data(), raw_t.data(), n,
                                   t_offset_us, block.data());
  TimeNs t_min_ns = 0, t_max_ns = 0;
  return r.x_max <= max_x && r.y_max <= max_y && r.p_max <= 1 &&
         MicrosecondsToNs(r.t_min, t_offset_us, &t_min_ns) &&
         MicrosecondsToNs(r.t_max, t_offset_us, &t_max_ns);
}

Expected<bool> DsecH5Decoder::ReadAnyLayout(std::uint64_t n, std::int64_t max_x,
                                            std::int64_t max_y) {
  AAVIO_RETURN_IF_ERROR(ReadRange(next_index, n));
  const ColumnRange x = RangeOf(xs.data(), n), y = RangeOf(ys.data(), n), p = RangeOf(ps.data(), n),
                    t = RangeOf(ts.data(), n);
  TimeNs t_min_ns = 0, t_max_ns = 0;
  if (!(x.min >= 0 && x.max <= max_x && y.min >= 0 && y.max <= max_y && p.min >= -1 && p.max <= 1 &&
        MicrosecondsToNs(t.min, t_offset_us, &t_min_ns) &&
        MicrosecondsToNs(t.max, t_offset_us, &t_max_ns))) {
    return false;
  }
  block.resize(n);
  for (std::uint64_t i = 0; i < n; ++i) {
    block[i] = {(ts[i] + t_offset_us) * kNsPerUs, static_cast<std::uint16_t>(xs[i]),
                static_cast<std::uint16_t>(ys[i]), static_cast<std::uint8_t>(ps[i] > 0 ? 1 : 0)};
  }
  return true;
}

Status DsecH5Decoder::ReadBlock() {
  const std::uint64_t n = std::min<std::uint64_t>(options.block_events, count - next_index);
  if (n == 0) return Status::Ok();
  // The block is checked by each column's extremes; the largest valid column and row: the
  // sensor's (a known size), else uint16's. Microseconds → nanoseconds is monotone, so if the
  // extremes of t convert without overflow, every t does. A block with a bad event is read
  // again as int64 and scanned for the message.
  const std::int64_t max_x = options.width > 0 ? std::min(options.width, 65536) - 1 : 65535;
  const std::int64_t max_y = options.width > 0 ? std::min(options.height, 65536) - 1 : 65535;
  Expected<bool> valid =
      dsec_layout ? ReadDsecLayout(n, max_x, max_y) : ReadAnyLayout(n, max_x, max_y);
  if (!valid) return valid.status();
  if (!*valid) {
    if (dsec_layout) AAVIO_RETURN_IF_ERROR(ReadRange(next_index, n));
    return DescribeBadEvent(n);
  }
  // In-order runs in one copy; an element out of order goes through Push (reordered or an error).
  const std::span<const events::Event> all(block);
  for (std::size_t i = 0; i < n;) {
    i += reorder.AppendInOrder(all.subspan(i));
    if (i == n) break;
    Status status = reorder.Push(block[i], "");
    if (!status.ok()) {
      return InvalidArgument(path + ": event " + std::to_string(next_index + i) + status.message());
    }
    ++i;
  }
  next_index += n;
  return Status::Ok();
}

Expected<std::int64_t> DsecH5Decoder::ReadT(std::uint64_t index) {
  h5::SilenceErrorPrinting();
  std::int64_t t = 0;
  AAVIO_RETURN_IF_ERROR(
      ReadSlab(datasets[3].get(), H5T_NATIVE_INT64, index, 1, &t, path, kFields[3]));
  return t;
}

DsecH5EventStream::~DsecH5EventStream() = default;

Expected<std::unique_ptr<DsecH5EventStream>> DsecH5EventStream::Open(const std::string& path,
                                                                     const StreamOptions& options) {
  h5::SilenceErrorPrinting();
  AAVIO_RETURN_IF_ERROR(CheckRegularFile(path, "DSEC events file"));
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    const std::string detail = h5::TakeErrorMessage();
    return ParseError(path + ": not a readable HDF5 file (truncated or not HDF5" +
                      (detail.empty() ? "" : ": " + detail) + ")");
  }
  // The whole open, and the first and last event of each dataset, in a child first.
  AAVIO_RETURN_IF_ERROR(h5::SurvivesInChild(path, [&] {
    Expected<std::unique_ptr<DsecH5EventStream>> probe = OpenHere(path, options);
    if (probe.ok() && (*probe)->decoder_->count > 0) {
      DsecH5Decoder& s = *(*probe)->decoder_;
      if (s.ReadRange(0, 1).ok()) (void)s.ReadRange(s.count - 1, 1);
    }
  }));
  return OpenHere(path, options);
}

Expected<std::unique_ptr<DsecH5EventStream>> DsecH5EventStream::OpenHere(
    const std::string& path, const StreamOptions& options) {
  auto s = std::make_unique<DsecH5Decoder>();
  s->path = path;
  s->options = options;
  s->reorder = ReorderBuffer<events::Event>(options.max_reorder_ns);
  s->file = h5::Handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!s->file.valid()) {
    const std::string detail = h5::TakeErrorMessage();
    return ParseError(path + ": cannot open as HDF5 (" + detail + ")");
  }
  // Reading is sequential, so each dataset only needs the chunk a block boundary cuts through:
  // 4 MB per dataset holds the largest chunks seen in DSEC-style files (memory stays bounded).
  h5::Handle access(H5Pcreate(H5P_DATASET_ACCESS), H5Pclose);
  H5Pset_chunk_cache(access.get(), 521, 4u << 20, 1.0);

  std::vector<std::string> missing;
  for (const char* name : kFields) {
    if (!h5::LinkExists(s->file.get(), name)) missing.emplace_back(name);
  }
  if (!missing.empty()) {
    std::string list;
    for (const std::string& m : missing)
      list += (list.empty() ? "" : ", ") + m;
    return ParseError(path + ": not a DSEC-layout event file: missing " + list +
                      " (expected /events/x, /events/y, /events/p, /events/t)");
  }
  std::int64_t n = -1;
  for (int i = 0; i < 4; ++i) {
    s->datasets[i] = h5::Handle(H5Dopen2(s->file.get(), kFields[i], access.get()), H5Dclose);
    if (!s->datasets[i].valid()) {
      return ParseError(path + ": cannot open " + kFields[i] + " (" + h5::TakeErrorMessage() + ")");
    }
    h5::Handle type(H5Dget_type(s->datasets[i].get()), H5Tclose);
    if (H5Tget_class(type.get()) != H5T_INTEGER) {
      return ParseError(path + ": " + kFields[i] +
                        " must hold integers (DSEC: x, y uint16; p uint8; t uint32 or int64)");
    }
    h5::Handle space(H5Dget_space(s->datasets[i].get()), H5Sclose);
    hsize_t dims[2] = {0, 0};
    if (H5Sget_simple_extent_ndims(space.get()) != 1) {
      return ParseError(path + ": " + kFields[i] + " must be one-dimensional (N,)");
    }
    H5Sget_simple_extent_dims(space.get(), dims, nullptr);
    if (n >= 0 && static_cast<std::int64_t>(dims[0]) != n) {
      return ParseError(path + ": /events/x, y, p and t must have the same length (" +
                        std::to_string(n) + " vs " + std::to_string(dims[0]) + " in " + kFields[i] +
                        ")");
    }
    n = static_cast<std::int64_t>(dims[0]);
    AAVIO_RETURN_IF_ERROR(h5::CheckReadable(s->datasets[i].get(), path, kFields[i]));
    s->file_types[i] = h5::Handle(H5Tget_native_type(type.get(), H5T_DIR_ASCEND), H5Tclose);
    const std::size_t size = s->file_types[i].valid() ? H5Tget_size(s->file_types[i].get()) : 0;
    if (size != 1 && size != 2 && size != 4 && size != 8) {
      return ParseError(path + ": " + kFields[i] +
                        " must hold integers of 1, 2, 4 or 8 bytes (DSEC: x, y uint16; p uint8; t "
                        "uint32 or int64)");
    }
  }
  s->count = static_cast<std::uint64_t>(n);
  auto is_unsigned = [&](int i, std::size_t bytes) {
    return H5Tget_size(s->file_types[i].get()) == bytes &&
           H5Tget_sign(s->file_types[i].get()) == H5T_SGN_NONE;
  };
  s->dsec_layout = is_unsigned(0, 2) && is_unsigned(1, 2) && is_unsigned(2, 1) && is_unsigned(3, 4);

  if (h5::LinkExists(s->file.get(), "/t_offset")) {
    h5::Handle d(H5Dopen2(s->file.get(), "/t_offset", H5P_DEFAULT), H5Dclose);
    h5::Handle space(H5Dget_space(d.get()), H5Sclose);
    if (H5Sget_simple_extent_npoints(space.get()) != 1) {
      return ParseError(path + ": /t_offset must hold exactly one number (µs)");
    }
    AAVIO_RETURN_IF_ERROR(h5::CheckReadable(d.get(), path, "/t_offset"));
    if (H5Dread(d.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, &s->t_offset_us) < 0) {
      return ParseError(path + ": cannot read /t_offset (" + h5::TakeErrorMessage() + ")");
    }
  }

  std::string notes;
  if (h5::LinkExists(s->file.get(), "/ms_to_idx")) {
    h5::Handle d(H5Dopen2(s->file.get(), "/ms_to_idx", H5P_DEFAULT), H5Dclose);
    h5::Handle space(H5Dget_space(d.get()), H5Sclose);
    const hssize_t m = H5Sget_simple_extent_npoints(space.get());
    // One entry per millisecond up to the last event: a longer index is corrupt, and is not
    // allocated (a file declared 2^50 entries; found by fuzzing).
    std::int64_t max_entries = 2;
    if (s->count > 0) {
      Expected<std::int64_t> last = s->ReadT(s->count - 1);
      if (last && *last > 0) max_entries = *last / 1000 + 2;
    }
    if (m > max_entries) {
      notes = "; ms_to_idx longer than the recording, ignored";
    } else {
      s->ms_to_idx.resize(m > 0 ? static_cast<std::size_t>(m) : 0);
      if (h5::CheckReadable(d.get(), path, "/ms_to_idx").ok() && m > 0 &&
          H5Dread(d.get(), H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, s->ms_to_idx.data()) >=
              0) {
        const bool monotone = std::is_sorted(s->ms_to_idx.begin(), s->ms_to_idx.end()) &&
                              s->ms_to_idx.back() <= s->count;
        if (!monotone) {
          s->ms_to_idx.clear();
          notes = "; ms_to_idx inconsistent, ignored";
        }
      } else {
        h5::TakeErrorMessage();
        s->ms_to_idx.clear();
        notes = "; ms_to_idx unreadable, ignored";
      }
    }
  }

  s->info.description = "DSEC events.h5: " + path + notes;
  s->info.count = n;
  if (n > 0) {
    Expected<std::int64_t> first = s->ReadT(0);
    if (!first) return first.status();
    Expected<std::int64_t> last = s->ReadT(static_cast<std::uint64_t>(n - 1));
    if (!last) return last.status();
    if (!MicrosecondsToNs(*first, s->t_offset_us, &s->info.t_first_ns) ||
        !MicrosecondsToNs(*last, s->t_offset_us, &s->info.t_last_ns)) {
      return ParseError(path +
                        ": /events/t + /t_offset is beyond what nanoseconds hold (292 "
                        "years): a corrupt file");
    }
  }
  return std::unique_ptr<DsecH5EventStream>(new DsecH5EventStream(std::move(s)));
}

const std::vector<std::uint64_t>& DsecH5EventStream::ms_to_idx() const {
  return decoder_->ms_to_idx;
}
std::int64_t DsecH5EventStream::t_offset_us() const {
  return decoder_->t_offset_us;
}

Status DsecH5Decoder::ReadUntil(TimeNs t_end_ns, std::vector<events::Event>* out) {
  while (!reorder.CanRelease(t_end_ns) && next_index < count) {
    AAVIO_RETURN_IF_ERROR(ReadBlock());
  }
  reorder.Release(t_end_ns, out);
  return Status::Ok();
}

Status DsecH5Decoder::Seek(TimeNs t_ns) {
  // Start early by the reorder window so late events at or after t_ns are not lost.
  const TimeNs from_ns = t_ns - options.max_reorder_ns;
  const std::int64_t rel_us = from_ns / kNsPerUs - t_offset_us - 1;
  std::uint64_t lo = 0;
  std::uint64_t hi = count;
  if (rel_us > 0 && !ms_to_idx.empty()) {
    // ms_to_idx[ms] = first event with t >= 1000 ms: a bracket for the binary search.
    const std::uint64_t ms = static_cast<std::uint64_t>(rel_us) / 1000;
    if (ms < ms_to_idx.size()) {
      lo = ms_to_idx[ms];
      if (ms + 1 < ms_to_idx.size()) hi = std::min(hi, ms_to_idx[ms + 1]);
    } else {
      lo = ms_to_idx.back();
    }
  }
  while (lo < hi) {  // first index with t >= rel_us
    const std::uint64_t mid = lo + (hi - lo) / 2;
    Expected<std::int64_t> t = ReadT(mid);
    if (!t) return t.status();
    if (*t < rel_us) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  next_index = lo;
  reorder.Reset(t_ns);
  return Status::Ok();
}

}  // namespace aavio::io

namespace aavio::io {

namespace {

Expected<cv::Mat> ReadRectifyMapHere(const std::string& path) {
  h5::Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid() || !h5::LinkExists(file.get(), "/rectify_map")) {
    h5::TakeErrorMessage();
    return ParseError(path + ": no /rectify_map dataset (expected float32 (height, width, 2))");
  }
  h5::Handle d(H5Dopen2(file.get(), "/rectify_map", H5P_DEFAULT), H5Dclose);
  AAVIO_RETURN_IF_ERROR(h5::CheckReadable(d.get(), path, "/rectify_map"));
  h5::Handle space(H5Dget_space(d.get()), H5Sclose);
  hsize_t dims[3] = {0, 0, 0};
  if (H5Sget_simple_extent_ndims(space.get()) != 3 ||
      (H5Sget_simple_extent_dims(space.get(), dims, nullptr), dims[2] != 2) || dims[0] == 0 ||
      dims[1] == 0 || dims[0] > 100000 || dims[1] > 100000) {
    return ParseError(path + ": /rectify_map must have shape (height, width, 2)");
  }
  cv::Mat map(static_cast<int>(dims[0]), static_cast<int>(dims[1]), CV_32FC2);
  if (H5Dread(d.get(), H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, map.data) < 0) {
    return IoError(path + ": reading /rectify_map failed (" + h5::TakeErrorMessage() + ")");
  }
  return map;
}

}  // namespace

Expected<cv::Mat> ReadDsecRectifyMap(const std::string& path) {
  h5::SilenceErrorPrinting();
  AAVIO_RETURN_IF_ERROR(CheckRegularFile(path, "DSEC rectification map"));
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    h5::TakeErrorMessage();
    return ParseError(path + ": not a readable HDF5 file (truncated or not HDF5)");
  }
  AAVIO_RETURN_IF_ERROR(h5::SurvivesInChild(path, [&] { (void)ReadRectifyMapHere(path); }));
  return ReadRectifyMapHere(path);
}

}  // namespace aavio::io
