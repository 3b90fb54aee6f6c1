#pragma once
/// AEDAT 4.0 files (iniVation DV recordings, `.aedat4`; docs/io.md): `#!AER-DAT4.0\r\n`, an int32
/// size and the IOHeader flatbuffer (compression NONE / LZ4 / LZ4_HIGH / ZSTD / ZSTD_HIGH, the
/// position of the file's data table, the XML description of each stream: type identifier EVTS,
/// IMUS, FRME, TRIG, sensor size), then packets — int32 stream id, int32 size, that many bytes
/// of a compressed size-prefixed flatbuffer — up to the data table (or the end of the file).
/// Events are 16-byte structs (t int64 µs, x int16, y int16, on bool); IMU samples are tables
/// (t µs, temperature, accelerometer [g], gyroscope [°/s], magnetometer), converted here to
/// m/s² and rad/s. Frames and triggers are skipped.
///
/// The file is indexed and decoded once when opened (count, time range; a corrupt or truncated
/// file fails there, naming the byte), then streamed packet by packet. A file with several event
/// (or IMU) streams needs `stream`: the stream id or its DV name (originalModuleName or
/// originalOutputName, e.g. "capture" for a DV recorder's one camera).

#include <memory>
#include <string>

#include "aavio/io/streams.hpp"

namespace aavio::io {

Expected<std::unique_ptr<EventStream>> OpenAedat4EventStream(const std::string& path,
                                                             const std::string& stream,
                                                             const StreamOptions& options);
Expected<std::unique_ptr<ImuStream>> OpenAedat4ImuStream(const std::string& path,
                                                         const std::string& stream,
                                                         const StreamOptions& options);

}  // namespace aavio::io
