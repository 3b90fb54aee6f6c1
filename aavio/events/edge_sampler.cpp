#include "aavio/events/edge_sampler.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <opencv2/imgproc.hpp>
#include <random>

namespace aavio::events {
namespace {

// The rectified position of raw pixel (x, y) if it lands on a valid rectified pixel.
bool Rectified(const geometry::RectificationMaps& maps, int x, int y, float* u, float* v) {
  if (maps.raw_valid.at<std::uint8_t>(y, x) == 0) return false;
  const cv::Vec2f r = maps.event_lut.at<cv::Vec2f>(y, x);
  *u = r[0];
  *v = r[1];
  return true;
}

// Integer in [0, n), the same on every platform (std distributions are not); the modulo bias is
// below n / 2^64.
std::size_t Below(std::mt19937_64& rng, std::size_t n) {
  return static_cast<std::size_t>(rng() % n);
}

// The k samples of one block with min_spacing_px > 0: candidates in descending count (ties in
// random order), first those with no sample within `spacing` px yet, then the rest.
void TakeSpaced(const std::vector<std::uint32_t>& candidates, const std::uint8_t* counts, int width,
                int height, int spacing, int k, std::mt19937_64& rng,
                std::vector<std::uint8_t>* taken, const std::function<void(std::uint32_t)>& take) {
  // Counting sort by count, descending (stable), then a shuffle within each count.
  std::array<int, 257> start{};
  for (const std::uint32_t pixel : candidates)
    ++start[static_cast<std::size_t>(256 - counts[pixel])];
  for (std::size_t c = 1; c < start.size(); ++c)
    start[c] += start[c - 1];
  std::vector<std::uint32_t> order(candidates.size());
  std::array<int, 257> next{};
  std::copy(start.begin(), start.end() - 1, next.begin() + 1);
  for (const std::uint32_t pixel : candidates)
    order[static_cast<std::size_t>(next[static_cast<std::size_t>(256 - counts[pixel])]++)] = pixel;
  for (std::size_t c = 1; c < start.size(); ++c) {
    const std::size_t first = static_cast<std::size_t>(c == 1 ? 0 : start[c - 1]);
    const std::size_t last = static_cast<std::size_t>(start[c]);
    for (std::size_t i = first; i + 1 < last; ++i)
      std::swap(order[i], order[i + Below(rng, last - i)]);
  }
  auto free_around = [&](std::uint32_t pixel) {
    const int x = static_cast<int>(pixel % static_cast<std::uint32_t>(width));
    const int y = static_cast<int>(pixel / static_cast<std::uint32_t>(width));
    for (int yy = std::max(0, y - spacing); yy <= std::min(height - 1, y + spacing); ++yy) {
      const std::uint8_t* row = taken->data() + static_cast<std::size_t>(yy) * width;
      for (int xx = std::max(0, x - spacing); xx <= std::min(width - 1, x + spacing); ++xx) {
        if (row[xx] != 0) return false;
      }
    }
    return true;
  };
  int got = 0;
  for (const bool spaced : {true, false}) {
    for (const std::uint32_t pixel : order) {
      if (got == k) return;
      if ((*taken)[pixel] != 0 || (spaced && !free_around(pixel))) continue;
      (*taken)[pixel] = 1;
      take(pixel);
      ++got;
    }
  }
}

}  // namespace

std::vector<int> BlockQuotas(const std::vector<int>& candidates, const EdgeSamplingConfig& config) {
  constexpr double kProportionalShare = 0.75, kBlockCapFraction = 0.5;  // [ESVO2]
  const std::size_t nb = candidates.size();
  std::vector<int> quota(nb, 0), cap(nb, 0);
  std::int64_t total = 0;
  for (const int n : candidates)
    total += n;
  if (total == 0) return quota;
  const double budget = config.num_points;
  std::int64_t given = 0;
  for (std::size_t b = 0; b < nb; ++b) {
    cap[b] = static_cast<int>(std::floor(kBlockCapFraction * candidates[b]));
    if (cap[b] == 0 && candidates[b] > 0) cap[b] = 1;  // a lone pixel may still be taken
    const int proportional = static_cast<int>(
        std::floor(kProportionalShare * budget * candidates[b] / static_cast<double>(total)));
    quota[b] = std::min(proportional, cap[b]);
    given += quota[b];
  }
  // The rest, evenly over the blocks with room, until the budget is met or all are full.
  std::int64_t left = config.num_points - given;
  while (left > 0) {
    std::int64_t with_room = 0;
    for (std::size_t b = 0; b < nb; ++b)
      with_room += quota[b] < cap[b] ? 1 : 0;
    if (with_room == 0) break;
    const std::int64_t share = std::max<std::int64_t>(1, left / with_room);
    for (std::size_t b = 0; b < nb && left > 0; ++b) {
      const std::int64_t add = std::min<std::int64_t>({share, cap[b] - quota[b], left});
      if (add <= 0) continue;
      quota[b] += static_cast<int>(add);
      left -= add;
    }
  }
  return quota;
}

namespace {

// Takes the k candidates of highest count: all above the threshold count c*, and a random part of
// those at c* (`tied` is scratch).
template <typename Take>
void TakeHighest(const std::vector<std::uint32_t>& candidates, const std::uint8_t* counts, int k,
                 std::mt19937_64& rng, std::vector<std::uint32_t>* tied, Take&& take) {
  std::array<int, 256> histogram{};
  for (const std::uint32_t pixel : candidates)
    ++histogram[counts[pixel]];
  int c_star = 255, above = 0;
  while (above + histogram[c_star] < k)
    above += histogram[c_star--];
  tied->clear();
  for (const std::uint32_t pixel : candidates) {
    if (counts[pixel] > c_star) {
      take(pixel);
    } else if (counts[pixel] == c_star) {
      tied->push_back(pixel);
    }
  }
  const std::size_t need = static_cast<std::size_t>(k - above);
  for (std::size_t i = 0; i < need; ++i) {  // partial Fisher–Yates
    std::swap((*tied)[i], (*tied)[i + Below(rng, tied->size() - i)]);
    take((*tied)[i]);
  }
}

}  // namespace

std::vector<EdgeSample> SampleAaMap(const AaMap& map, const geometry::RectificationMaps& maps,
                                    const EdgeSamplingConfig& config, std::uint64_t seed) {
  const int width = map.counts.cols;
  const std::uint8_t* counts = map.counts.ptr<std::uint8_t>();
  const std::uint8_t* valid = maps.raw_valid.ptr<std::uint8_t>();
  // Candidates per block: active pixels that rectify onto valid pixels (indices only; samples
  // are made for the chosen ones).
  std::vector<std::vector<std::uint32_t>> candidates(map.blocks.size());
  std::vector<int> sizes(map.blocks.size(), 0);
  for (std::size_t b = 0; b < map.blocks.size(); ++b) {
    candidates[b].reserve(map.blocks[b].active.size());
    for (const std::uint32_t pixel : map.blocks[b].active) {
      if (valid[pixel] != 0) candidates[b].push_back(pixel);
    }
    sizes[b] = static_cast<int>(candidates[b].size());
  }
  const std::vector<int> quota = BlockQuotas(sizes, config);

  std::mt19937_64 rng(seed);
  std::vector<EdgeSample> samples;
  samples.reserve(static_cast<std::size_t>(config.num_points));
  auto take = [&](std::uint32_t pixel) {
    EdgeSample s;
    s.x = static_cast<std::uint16_t>(pixel % static_cast<std::uint32_t>(width));
    s.y = static_cast<std::uint16_t>(pixel / static_cast<std::uint32_t>(width));
    const cv::Vec2f r = maps.event_lut.at<cv::Vec2f>(s.y, s.x);
    s.u = r[0];
    s.v = r[1];
    s.count = counts[pixel];
    samples.push_back(s);
  };
  if (config.min_spacing_px > 0) {
    std::vector<std::uint8_t> taken(map.counts.total(), 0);
    for (std::size_t b = 0; b < candidates.size(); ++b) {
      if (quota[b] > 0) {
        TakeSpaced(candidates[b], counts, width, map.counts.rows, config.min_spacing_px, quota[b],
                   rng, &taken, take);
      }
    }
    return samples;
  }
  std::vector<std::uint32_t> tied;
  for (std::size_t b = 0; b < candidates.size(); ++b) {
    if (quota[b] > 0) TakeHighest(candidates[b], counts, quota[b], rng, &tied, take);
  }
  return samples;
}

std::vector<EdgeSample> SelectNewestEvents(std::span<const Event> events, TimeNs t_ns,
                                           const geometry::RectificationMaps& maps,
                                           const EdgeSamplingConfig& config) {
  const TimeNs window_ns = SecondsToNs(kNewestEventsWindowMs * 1e-3);
  std::vector<EdgeSample> samples;
  for (auto it = events.rbegin(); it != events.rend(); ++it) {
    if (it->t_ns > t_ns) continue;
    if (it->t_ns <= t_ns - window_ns || static_cast<int>(samples.size()) >= config.num_points) {
      break;
    }
    EdgeSample s;
    s.x = it->x, s.y = it->y, s.count = 1;
    if (Rectified(maps, s.x, s.y, &s.u, &s.v)) samples.push_back(s);
  }
  return samples;
}

std::vector<EdgeSample> SelectNewestEventsAtCount(std::span<const Event> events, TimeNs t_ns,
                                                  const geometry::RectificationMaps& maps,
                                                  EdgeSamplingConfig config, std::size_t count) {
  config.num_points = static_cast<int>(std::max<std::size_t>(1, count));
  return SelectNewestEvents(events, t_ns, maps, config);
}

}  // namespace aavio::events
