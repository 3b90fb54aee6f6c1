#include "aavio/io/decompression.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <limits>
#include <string>

#include "aavio/common/format.hpp"

namespace aavio::io {

namespace {

// A stated size gets one spare byte: the decoder can then read the frame's end (and say if the
// data are longer than stated) without running out of room. The stated size is not trusted for
// the first allocation (a corrupt header may claim gigabytes): the buffer starts at what the
// input plausibly holds and doubles as the data really decompress, up to the stated size.
std::size_t Capacity(std::size_t expected_size) {
  return expected_size > 0 ? expected_size + 1 : std::numeric_limits<std::size_t>::max();
}
std::size_t InitialSize(std::size_t in_size, std::size_t expected_size) {
  return std::min(Capacity(expected_size), 4 * in_size + (1 << 20));
}
// Room for more output; false when the stated size is already exceeded.
bool Grow(std::vector<unsigned char>* out, std::size_t expected_size) {
  if (out->size() >= Capacity(expected_size)) return false;
  out->resize(std::min(Capacity(expected_size), 2 * out->size()));
  return true;
}

Status CheckSize(const char* format, std::size_t got, std::size_t expected_size) {
  if (expected_size > 0 && got != expected_size) {
    return ParseError(StrFormat("%s data decompress to %zu bytes, the container says %zu", format,
                                got, expected_size));
  }
  return Status::Ok();
}

}  // namespace

Status DecompressLz4Frame(std::span<const unsigned char> in, std::size_t expected_size,
                          std::vector<unsigned char>* out) {
  LZ4F_dctx* dctx = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&dctx, LZ4F_VERSION)))
    return IoError("cannot create an LZ4 decompression context");
  out->resize(InitialSize(in.size(), expected_size));
  std::size_t in_at = 0, out_at = 0, hint = 1;
  while (hint != 0 && in_at < in.size()) {
    if (out_at == out->size() && !Grow(out, expected_size)) break;  // more than stated
    std::size_t out_n = out->size() - out_at, in_n = in.size() - in_at;
    hint = LZ4F_decompress(dctx, out->data() + out_at, &out_n, in.data() + in_at, &in_n, nullptr);
    if (LZ4F_isError(hint)) {
      LZ4F_freeDecompressionContext(dctx);
      return ParseError(std::string("corrupt LZ4 data (") + LZ4F_getErrorName(hint) + ")");
    }
    in_at += in_n;
    out_at += out_n;
    if (in_n == 0 && out_n == 0) break;
  }
  LZ4F_freeDecompressionContext(dctx);
  if (hint != 0) return ParseError("the LZ4 frame ends early (truncated data)");
  out->resize(out_at);
  return CheckSize("LZ4", out_at, expected_size);
}

Status DecompressZstd(std::span<const unsigned char> in, std::size_t expected_size,
                      std::vector<unsigned char>* out) {
  ZSTD_DStream* z = ZSTD_createDStream();
  if (z == nullptr) return IoError("cannot create a Zstandard decompression context");
  ZSTD_initDStream(z);
  out->resize(InitialSize(in.size(), expected_size));
  ZSTD_inBuffer src{in.data(), in.size(), 0};
  std::size_t out_at = 0, left = 1;
  while (left != 0) {
    if (out_at == out->size() && !Grow(out, expected_size)) break;
    ZSTD_outBuffer dst{out->data() + out_at, out->size() - out_at, 0};
    left = ZSTD_decompressStream(z, &dst, &src);
    if (ZSTD_isError(left)) {
      ZSTD_freeDStream(z);
      return ParseError(std::string("corrupt Zstandard data (") + ZSTD_getErrorName(left) + ")");
    }
    out_at += dst.pos;
    if (src.pos == src.size && dst.pos == 0) break;
  }
  ZSTD_freeDStream(z);
  if (left != 0) return ParseError("the Zstandard frame ends early (truncated data)");
  out->resize(out_at);
  return CheckSize("Zstandard", out_at, expected_size);
}

}  // namespace aavio::io
