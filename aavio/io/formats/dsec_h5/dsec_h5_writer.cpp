#include "aavio/io/formats/dsec_h5/dsec_h5_writer.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "aavio/io/formats/dsec_h5/hdf5_util.hpp"

namespace aavio::io {

namespace {

constexpr H5Z_filter_t kBloscFilter = 32001;

constexpr std::int64_t FloorDiv(std::int64_t a, std::int64_t b) {
  return a / b - ((a % b != 0) && ((a < 0) != (b < 0)) ? 1 : 0);
}

/// An extendable 1-D dataset that grows by appending.
struct Column {
  h5::Handle dataset;
  hid_t mem_type = -1;
  hsize_t size = 0;
};

}  // namespace

struct DsecH5EventWriter::State {
  std::string path;
  DsecH5WriterOptions options;
  h5::Handle file;
  h5::Handle group;
  std::array<Column, 4> columns;  // x, y, p, t
  std::int64_t t_offset_us = 0;
  bool offset_set = false;
  std::int64_t last_t_us = std::numeric_limits<std::int64_t>::min();
  std::uint64_t written = 0;
  std::vector<std::uint64_t> ms_to_idx;
  std::vector<std::uint16_t> xs, ys;
  std::vector<std::uint8_t> ps;
  std::vector<std::uint32_t> ts;
  bool closed = false;

  Expected<h5::Handle> CreatePlist(std::size_t chunk) const;
  Status CreateColumn(hid_t parent, const char* name, hid_t file_type, hid_t mem_type, Column* c);
  Status Append(Column* c, const void* data, std::size_t n, const char* name);
  Status Flush();
};

Expected<h5::Handle> DsecH5EventWriter::State::CreatePlist(std::size_t chunk) const {
  h5::Handle plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  H5Pset_obj_track_times(plist.get(), 0);  // no modification times: same events, same bytes
  const hsize_t chunk_dims = chunk;
  H5Pset_chunk(plist.get(), 1, &chunk_dims);
  if (options.compress) {
    if (H5Zfilter_avail(kBloscFilter) <= 0) {
      H5Eclear2(H5E_DEFAULT);
      return FailedPrecondition(path +
                                ": cannot compress with blosc: the HDF5 blosc filter is not "
                                "installed (Debian package hdf5-filter-plugin-blosc-serial)");
    }
    // cd_values[0..3] are filled in by the filter; clevel, shuffle (2 = bit), compressor (5 =
    // zstd).
    const unsigned cd[7] = {0, 0, 0, 0, static_cast<unsigned>(options.compression_level), 2, 5};
    if (H5Pset_filter(plist.get(), kBloscFilter, H5Z_FLAG_MANDATORY, 7, cd) < 0) {
      return IoError(path + ": cannot set the blosc filter (" + h5::TakeErrorMessage() + ")");
    }
  }
  return plist;
}

Status DsecH5EventWriter::State::CreateColumn(hid_t parent, const char* name, hid_t file_type,
                                              hid_t mem_type, Column* c) {
  const hsize_t zero = 0;
  const hsize_t unlimited = H5S_UNLIMITED;
  h5::Handle space(H5Screate_simple(1, &zero, &unlimited), H5Sclose);
  Expected<h5::Handle> plist = CreatePlist(options.chunk_events);
  if (!plist) return plist.status();
  c->dataset = h5::Handle(
      H5Dcreate2(parent, name, file_type, space.get(), H5P_DEFAULT, plist->get(), H5P_DEFAULT),
      H5Dclose);
  if (!c->dataset.valid()) {
    return IoError(path + ": cannot create " + name + " (" + h5::TakeErrorMessage() + ")");
  }
  c->mem_type = mem_type;
  return Status::Ok();
}

Status DsecH5EventWriter::State::Append(Column* c, const void* data, std::size_t n,
                                        const char* name) {
  if (n == 0) return Status::Ok();
  const hsize_t new_size = c->size + n;
  const hsize_t start = c->size;
  const hsize_t count = n;
  if (H5Dset_extent(c->dataset.get(), &new_size) < 0) {
    return IoError(path + ": cannot extend " + name + " (" + h5::TakeErrorMessage() + ")");
  }
  h5::Handle space(H5Dget_space(c->dataset.get()), H5Sclose);
  h5::Handle mem(H5Screate_simple(1, &count, nullptr), H5Sclose);
  H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, &start, nullptr, &count, nullptr);
  if (H5Dwrite(c->dataset.get(), c->mem_type, mem.get(), space.get(), H5P_DEFAULT, data) < 0) {
    return IoError(path + ": writing " + name + " failed (disk full?) (" + h5::TakeErrorMessage() +
                   ")");
  }
  c->size = new_size;
  return Status::Ok();
}

Status DsecH5EventWriter::State::Flush() {
  AAVIO_RETURN_IF_ERROR(Append(&columns[0], xs.data(), xs.size(), "/events/x"));
  AAVIO_RETURN_IF_ERROR(Append(&columns[1], ys.data(), ys.size(), "/events/y"));
  AAVIO_RETURN_IF_ERROR(Append(&columns[2], ps.data(), ps.size(), "/events/p"));
  AAVIO_RETURN_IF_ERROR(Append(&columns[3], ts.data(), ts.size(), "/events/t"));
  xs.clear();
  ys.clear();
  ps.clear();
  ts.clear();
  return Status::Ok();
}

DsecH5EventWriter::DsecH5EventWriter(std::unique_ptr<State> state) : s_(std::move(state)) {}

DsecH5EventWriter::~DsecH5EventWriter() {
  if (s_ && !s_->closed) (void)Close();
}

Expected<std::unique_ptr<DsecH5EventWriter>> DsecH5EventWriter::Create(
    const std::string& path, const DsecH5WriterOptions& options) {
  h5::SilenceErrorPrinting();
  if (options.chunk_events == 0 || options.compression_level < 0 || options.compression_level > 9) {
    return InvalidArgument(path + ": chunk_events must be > 0 and compression_level in [0, 9]");
  }
  auto s = std::make_unique<State>();
  s->path = path;
  s->options = options;
  s->file = h5::Handle(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (!s->file.valid()) {
    return IoError(path + ": cannot create (" + h5::TakeErrorMessage() + ")");
  }
  h5::Handle group_plist(H5Pcreate(H5P_GROUP_CREATE), H5Pclose);
  H5Pset_obj_track_times(group_plist.get(), 0);
  s->group = h5::Handle(
      H5Gcreate2(s->file.get(), "events", H5P_DEFAULT, group_plist.get(), H5P_DEFAULT), H5Gclose);
  const hid_t g = s->group.get();
  AAVIO_RETURN_IF_ERROR(s->CreateColumn(g, "x", H5T_STD_U16LE, H5T_NATIVE_UINT16, &s->columns[0]));
  AAVIO_RETURN_IF_ERROR(s->CreateColumn(g, "y", H5T_STD_U16LE, H5T_NATIVE_UINT16, &s->columns[1]));
  AAVIO_RETURN_IF_ERROR(s->CreateColumn(g, "p", H5T_STD_U8LE, H5T_NATIVE_UINT8, &s->columns[2]));
  AAVIO_RETURN_IF_ERROR(s->CreateColumn(g, "t", H5T_STD_U32LE, H5T_NATIVE_UINT32, &s->columns[3]));
  if (options.t_offset_us) {
    s->t_offset_us = *options.t_offset_us;
    s->offset_set = true;
  }
  return std::unique_ptr<DsecH5EventWriter>(new DsecH5EventWriter(std::move(s)));
}

Status DsecH5EventWriter::Write(std::span<const events::Event> events) {
  State& s = *s_;
  if (s.closed) return FailedPrecondition(s.path + ": writer already closed");
  for (const events::Event& e : events) {
    const std::int64_t t_us = FloorDiv(e.t_ns + kNsPerUs / 2, kNsPerUs);  // nearest µs
    if (!s.offset_set) {
      s.t_offset_us = FloorDiv(t_us, 1000) * 1000;
      s.offset_set = true;
    }
    if (t_us < s.last_t_us) {
      return InvalidArgument(s.path + ": events must be written in time order (event at " +
                             FormatSecondsNs(e.t_ns) + " s after one at " +
                             FormatSecondsNs(s.last_t_us * kNsPerUs) + " s)");
    }
    const std::int64_t rel = t_us - s.t_offset_us;
    if (rel < 0 || rel > std::numeric_limits<std::uint32_t>::max()) {
      return InvalidArgument(s.path + ": event at " + FormatSecondsNs(e.t_ns) +
                             " s does not fit the uint32 µs t of the DSEC layout (t_offset " +
                             std::to_string(s.t_offset_us) + " µs; at most 71.6 minutes per file)");
    }
    while (static_cast<std::int64_t>(s.ms_to_idx.size()) * 1000 <= rel) {
      s.ms_to_idx.push_back(s.written);
    }
    s.xs.push_back(e.x);
    s.ys.push_back(e.y);
    s.ps.push_back(e.polarity ? 1 : 0);
    s.ts.push_back(static_cast<std::uint32_t>(rel));
    s.last_t_us = t_us;
    ++s.written;
    if (s.xs.size() >= s.options.chunk_events) AAVIO_RETURN_IF_ERROR(s.Flush());
  }
  return Status::Ok();
}

Status DsecH5EventWriter::Close() {
  State& s = *s_;
  if (s.closed) return Status::Ok();
  s.closed = true;
  AAVIO_RETURN_IF_ERROR(s.Flush());
  Column ms;
  const std::size_t chunk =
      std::max<std::size_t>(1, std::min<std::size_t>(s.ms_to_idx.size(), 1 << 14));
  const hsize_t zero = 0;
  const hsize_t unlimited = H5S_UNLIMITED;
  {
    h5::Handle space(H5Screate_simple(1, &zero, &unlimited), H5Sclose);
    Expected<h5::Handle> plist = s.CreatePlist(chunk);
    if (!plist) return plist.status();
    ms.dataset = h5::Handle(H5Dcreate2(s.file.get(), "ms_to_idx", H5T_STD_U64LE, space.get(),
                                       H5P_DEFAULT, plist->get(), H5P_DEFAULT),
                            H5Dclose);
    ms.mem_type = H5T_NATIVE_UINT64;
    if (!ms.dataset.valid()) return IoError(s.path + ": cannot create /ms_to_idx");
    AAVIO_RETURN_IF_ERROR(s.Append(&ms, s.ms_to_idx.data(), s.ms_to_idx.size(), "/ms_to_idx"));
  }
  {
    h5::Handle space(H5Screate(H5S_SCALAR), H5Sclose);
    h5::Handle plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    H5Pset_obj_track_times(plist.get(), 0);
    h5::Handle d(H5Dcreate2(s.file.get(), "t_offset", H5T_STD_I64LE, space.get(), H5P_DEFAULT,
                            plist.get(), H5P_DEFAULT),
                 H5Dclose);
    if (!d.valid() ||
        H5Dwrite(d.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, &s.t_offset_us) < 0) {
      return IoError(s.path + ": cannot write /t_offset (" + h5::TakeErrorMessage() + ")");
    }
  }
  for (Column& c : s.columns)
    c.dataset.Reset();
  ms.dataset.Reset();
  s.group.Reset();
  if (H5Fclose(s.file.Release()) < 0) {
    return IoError(s.path + ": closing failed (" + h5::TakeErrorMessage() + ")");
  }
  return Status::Ok();
}

}  // namespace aavio::io
