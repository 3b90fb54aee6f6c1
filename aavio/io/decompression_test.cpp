#include "aavio/io/decompression.hpp"

#include <gtest/gtest.h>
#include <lz4frame.h>
#include <zstd.h>

#include <random>

namespace aavio::io {
namespace {

std::vector<unsigned char> Data(std::size_t n) {
  std::mt19937 rng(7);
  std::vector<unsigned char> d(n);
  for (std::size_t i = 0; i < n; ++i)
    d[i] = static_cast<unsigned char>(i % 97 < 60 ? i % 7 : rng() & 0xFF);  // some redundancy
  return d;
}

std::vector<unsigned char> Lz4(const std::vector<unsigned char>& d) {
  std::vector<unsigned char> out(LZ4F_compressFrameBound(d.size(), nullptr));
  out.resize(LZ4F_compressFrame(out.data(), out.size(), d.data(), d.size(), nullptr));
  return out;
}

std::vector<unsigned char> Zstd(const std::vector<unsigned char>& d) {
  std::vector<unsigned char> out(ZSTD_compressBound(d.size()));
  out.resize(ZSTD_compress(out.data(), out.size(), d.data(), d.size(), 3));
  return out;
}

TEST(Decompression, BothFormatsWithAndWithoutAStatedSize) {
  // Larger than the initial guess of 4× the input when the size is not stated.
  std::vector<unsigned char> d(300000, 0);
  d[1234] = 9;
  for (auto [name, packed, fn] : {std::tuple{"lz4", Lz4(d), &DecompressLz4Frame},
                                  std::tuple{"zstd", Zstd(d), &DecompressZstd}}) {
    for (std::size_t stated : {std::size_t{0}, d.size()}) {
      std::vector<unsigned char> out;
      const Status s = fn(packed, stated, &out);
      EXPECT_TRUE(s.ok()) << name << ": " << s.message();
      EXPECT_EQ(out, d) << name << ", stated " << stated;
    }
  }
}

TEST(Decompression, WrongSizesTruncatedAndCorruptDataAreErrors) {
  const std::vector<unsigned char> d = Data(50000);
  for (auto [name, packed, fn] : {std::tuple{"LZ4", Lz4(d), &DecompressLz4Frame},
                                  std::tuple{"Zstandard", Zstd(d), &DecompressZstd}}) {
    std::vector<unsigned char> out;
    const Status small = fn(packed, d.size() - 10, &out);
    EXPECT_FALSE(small.ok()) << name;
    const Status large = fn(packed, d.size() + 10, &out);
    EXPECT_NE(large.message().find("the container says 50010"), std::string::npos)
        << name << ": " << large.message();
    std::vector<unsigned char> cut(packed.begin(), packed.begin() + packed.size() / 2);
    const Status truncated = fn(cut, 0, &out);
    EXPECT_NE(truncated.message().find("ends early"), std::string::npos)
        << name << ": " << truncated.message();
    // A broken frame header (without checksums, altered literals would pass unseen).
    std::vector<unsigned char> bad = packed;
    bad[1] ^= 0x5A;
    const Status corrupt = fn(bad, d.size(), &out);
    EXPECT_NE(corrupt.message().find(std::string("corrupt ") + name), std::string::npos)
        << name << ": " << corrupt.message();
  }
}

}  // namespace
}  // namespace aavio::io
