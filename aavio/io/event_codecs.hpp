#pragma once
/// Decoders of the packed event encodings that cameras stream, word by word with the state the
/// encodings carry between words (and, in ROS 2 packets, between messages):
///   EVT 2.0   Prophesee, 32-bit words (prophesee_raw.hpp gives the layout);
///   EVT 3.0   Prophesee, 16-bit words, 24-bit µs time unwrapped here;
///   libcaer   iniVation through libcaer_driver: 8 bytes per event, uint32 data (x bits 31..17,
///             y bits 16..2, polarity bit 1) and an int32 µs timestamp; t = time_base [ns] +
///             1000 · timestamp, the 31-bit timestamp's wrap inside a packet added;
///   libcaer_cmp  the same cameras, compressed by libcaer_driver into 16-bit words (defined by
///             ros-event-camera's event_camera_codecs): code in bits 15..12 — 0 TIME_HIGH and
///             1 TIME_LOW (12 bits each, µs since time_base, both reset at each packet), 2 ADDR_X
///             (x, 11 bits), 3 ADDR_Y (y, polarity bit 11: one event at the last x), 4 VECT_BASE_Y
///             (y and polarity of a vector), 5 VECT_8 (a mask of events at y, y + 1, … y + 7 of
///             the last x; the base then moves 8 down).
/// Events before the first EVT time word have no time and are skipped, as Metavision does.

#include <cstdint>
#include <string>

#include "aavio/common/format.hpp"
#include "aavio/common/status.hpp"
#include "aavio/common/time.hpp"
#include "aavio/events/event.hpp"

namespace aavio::io {

enum class EventEncoding { kEvt2, kEvt3, kLibcaer, kLibcaerCmp };

class EventWordDecoder {
 public:
  /// `width`/`height` bound the coordinates (0: unchecked); `source` names the file in errors.
  EventWordDecoder(EventEncoding encoding, int width, int height, std::string source)
      : encoding_(encoding), width_(width), height_(height), source_(std::move(source)) {}

  std::size_t word_bytes() const {
    switch (encoding_) {
      case EventEncoding::kEvt2:
        return 4;
      case EventEncoding::kEvt3:
        return 2;
      case EventEncoding::kLibcaer:
        return 8;
      case EventEncoding::kLibcaerCmp:
        return 2;
    }
    return 1;
  }
  /// The host time of a libcaer packet's timestamps [ns]; set before each packet.
  void SetTimeBase(std::uint64_t time_base_ns) { time_base_ns_ = time_base_ns; }

  /// Decodes the whole words of `data`; `offset` locates its first byte for error messages.
  /// `emit(event, byte offset)` receives each event.
  template <typename Emit>
  Status Decode(const unsigned char* data, std::size_t bytes, std::int64_t offset, Emit&& emit) {
    switch (encoding_) {
      case EventEncoding::kEvt2:
        return DecodeEvt2(data, bytes, offset, emit);
      case EventEncoding::kEvt3:
        return DecodeEvt3(data, bytes, offset, emit);
      case EventEncoding::kLibcaer:
        return DecodeLibcaer(data, bytes, offset, emit);
      case EventEncoding::kLibcaerCmp:
        return DecodeLibcaerCmp(data, bytes, offset, emit);
    }
    return Status::Ok();
  }

 private:
  static std::uint32_t Le32(const unsigned char* p) {
    return static_cast<std::uint32_t>(p[0]) | (std::uint32_t{p[1]} << 8) |
           (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[3]} << 24);
  }

  template <typename Emit>
  Status DecodeEvt2(const unsigned char* data, std::size_t bytes, std::int64_t offset, Emit& emit) {
    for (std::size_t k = 0; k + 4 <= bytes; k += 4) {
      const std::uint32_t w = Le32(data + k);
      const unsigned type = w >> 28;
      const std::int64_t at = offset + static_cast<std::int64_t>(k);
      if (type <= 1) {
        if (!have_time_) continue;
        const std::int64_t t_us = static_cast<std::int64_t>((time_high_ << 6) | ((w >> 22) & 0x3F));
        AAVIO_RETURN_IF_ERROR(Emit1(t_us * kNsPerUs, (w >> 11) & 0x7FF, w & 0x7FF, type, at, emit));
      } else if (type == 0x8) {
        time_high_ = w & 0x0FFFFFFF;
        have_time_ = true;
      } else if (type != 0xA && type != 0xE && type != 0xF) {
        return Corrupt(type, at);
      }
    }
    return Status::Ok();
  }

  template <typename Emit>
  Status DecodeEvt3(const unsigned char* data, std::size_t bytes, std::int64_t offset, Emit& emit) {
    for (std::size_t k = 0; k + 2 <= bytes; k += 2) {
      const unsigned w = static_cast<unsigned>(data[k]) | (static_cast<unsigned>(data[k + 1]) << 8);
      const unsigned type = w >> 12;
      const std::int64_t at = offset + static_cast<std::int64_t>(k);
      switch (type) {
        case 0x0:
          y_ = w & 0x7FF;
          break;
        case 0x2:
          if (have_time_)
            AAVIO_RETURN_IF_ERROR(Emit1(Evt3TimeNs(), w & 0x7FF, y_, (w >> 11) & 1, at, emit));
          break;
        case 0x3:
          base_x_ = w & 0x7FF;
          polarity_ = (w >> 11) & 1;
          break;
        case 0x4:
        case 0x5: {
          const unsigned bits = type == 0x4 ? 12 : 8;
          if (have_time_) {
            for (unsigned b = 0; b < bits; ++b) {
              if ((w >> b) & 1)
                AAVIO_RETURN_IF_ERROR(Emit1(Evt3TimeNs(), base_x_ + b, y_, polarity_, at, emit));
            }
          }
          base_x_ += bits;
          break;
        }
        case 0x6:
          time_low_ = w & 0xFFF;
          break;
        case 0x8: {
          const std::uint64_t high = w & 0xFFF;
          if (have_time_ && high < time_high_) ++wraps_;  // the 24-bit time wrapped
          time_high_ = high;
          have_time_ = true;
          break;
        }
        case 0x7:
        case 0xA:
        case 0xE:
        case 0xF:
          break;  // continued, trigger and vendor words
        default:
          return Corrupt(type, at);
      }
    }
    return Status::Ok();
  }

  template <typename Emit>
  Status DecodeLibcaer(const unsigned char* data, std::size_t bytes, std::int64_t offset,
                       Emit& emit) {
    std::uint64_t base = time_base_ns_;
    std::int64_t last_us = 0;
    for (std::size_t k = 0; k + 8 <= bytes; k += 8) {
      const std::uint32_t d = Le32(data + k);
      const std::int64_t us = static_cast<std::int32_t>(Le32(data + k + 4));
      if (k > 0 && us < last_us) base += (std::uint64_t{1} << 31) * 1000;  // the timestamp wrapped
      last_us = us;
      const TimeNs t = static_cast<TimeNs>(base) + us * 1000;
      AAVIO_RETURN_IF_ERROR(Emit1(t, (d >> 17) & 0x7FFF, (d >> 2) & 0x7FFF, (d >> 1) & 1,
                                  offset + static_cast<std::int64_t>(k), emit));
    }
    return Status::Ok();
  }

  template <typename Emit>
  Status DecodeLibcaerCmp(const unsigned char* data, std::size_t bytes, std::int64_t offset,
                          Emit& emit) {
    std::uint64_t high = 0, low = 0;  // reset at each packet
    unsigned x = 0, base_y = 0, polarity = 0;
    for (std::size_t k = 0; k + 2 <= bytes; k += 2) {
      const unsigned w = static_cast<unsigned>(data[k]) | (static_cast<unsigned>(data[k + 1]) << 8);
      const unsigned code = w >> 12;
      const std::int64_t at = offset + static_cast<std::int64_t>(k);
      const auto t = [&] { return static_cast<TimeNs>(time_base_ns_ + (high | low) * 1000); };
      switch (code) {
        case 0x0:
          high = static_cast<std::uint64_t>(w & 0xFFF) << 12;
          break;
        case 0x1:
          low = w & 0xFFF;
          break;
        case 0x2:
          x = w & 0x7FF;
          break;
        case 0x3:
          AAVIO_RETURN_IF_ERROR(Emit1(t(), x, w & 0x7FF, (w >> 11) & 1, at, emit));
          break;
        case 0x4:
          base_y = w & 0x7FF;
          polarity = (w >> 11) & 1;
          break;
        case 0x5:
          for (unsigned b = 0; b < 8; ++b) {
            if ((w >> b) & 1) AAVIO_RETURN_IF_ERROR(Emit1(t(), x, base_y + b, polarity, at, emit));
          }
          base_y += 8;
          break;
        default:
          return Corrupt(code, at);
      }
    }
    return Status::Ok();
  }

  TimeNs Evt3TimeNs() const {
    return static_cast<TimeNs>((wraps_ << 24) | (time_high_ << 12) | time_low_) * kNsPerUs;
  }
  template <typename Emit>
  Status Emit1(TimeNs t_ns, unsigned x, unsigned y, unsigned polarity, std::int64_t at,
               Emit& emit) {
    if (width_ > 0 && (x >= static_cast<unsigned>(width_) || y >= static_cast<unsigned>(height_))) {
      return InvalidArgument(
          StrFormat("%s: event at (%u, %u) outside the %d x %d sensor, byte %lld: "
                    "a corrupt file, or a header with the wrong geometry",
                    source_.c_str(), x, y, width_, height_, static_cast<long long>(at)));
    }
    emit(events::Event{t_ns, static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y),
                       static_cast<std::uint8_t>(polarity)},
         at);
    return Status::Ok();
  }
  Status Corrupt(unsigned type, std::int64_t at) const {
    return InvalidArgument(
        StrFormat("%s: word type 0x%X at byte %lld is not %s: a corrupt file, or "
                  "one whose header names the wrong encoding",
                  source_.c_str(), type, static_cast<long long>(at),
                  encoding_ == EventEncoding::kEvt2   ? "EVT 2.0"
                  : encoding_ == EventEncoding::kEvt3 ? "EVT 3.0"
                                                      : "libcaer_cmp"));
  }

  EventEncoding encoding_;
  int width_, height_;
  std::string source_;
  bool have_time_ = false;
  std::uint64_t time_high_ = 0, time_low_ = 0, wraps_ = 0;
  unsigned y_ = 0, base_x_ = 0, polarity_ = 0;
  std::uint64_t time_base_ns_ = 0;
};

}  // namespace aavio::io
