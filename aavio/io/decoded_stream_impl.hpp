#pragma once
/// DecodedStream's members, for the .cpp of a format whose decoder is complete there:
///   template class DecodedStream<events::Event, MyDecoder>;

#include <memory>
#include <utility>
#include <vector>

#include "aavio/io/streams.hpp"

namespace aavio::io {

template <typename T, typename Decoder>
DecodedStream<T, Decoder>::DecodedStream(std::unique_ptr<Decoder> decoder)
    : decoder_(std::move(decoder)) {}

template <typename T, typename Decoder>
DecodedStream<T, Decoder>::~DecodedStream() = default;

template <typename T, typename Decoder>
const StreamInfo& DecodedStream<T, Decoder>::info() const {
  return decoder_->info;
}

template <typename T, typename Decoder>
Status DecodedStream<T, Decoder>::ReadUntil(TimeNs t_end_ns, std::vector<T>* out) {
  return decoder_->ReadUntil(t_end_ns, out);
}

template <typename T, typename Decoder>
Status DecodedStream<T, Decoder>::Seek(TimeNs t_ns) {
  return decoder_->Seek(t_ns);
}

template <typename T, typename Decoder>
bool DecodedStream<T, Decoder>::AtEnd() const {
  return decoder_->AtEnd();
}

}  // namespace aavio::io
