// libFuzzer target: the pair selection of `duskmap features eval`
// (slam/features/eval/eval_pairs.h) and how the sequence layouts apply it
// (SelectSequencePairs, image_sequence.h).
//   byte 0: bit 0 set: the rest is a `--pairs` spec (ParsePairList), else the
//           text of a `--pairs-file` list (ParsePairListText, "fuzz.txt").
// Every selector is then parsed as an image pair (ParseImagePairSelector), and
// the list is applied to two static sequences held in memory ("day": images
// 1..4, "dusk/cam": images 1, 2, 7).
// Each step either throws duskmap::Error, one line starting with where the
// text came from, or keeps what eval_pairs.h and image_sequence.h promise:
// no selector twice, none empty or padded; image pairs of two different
// indices in 1..999999; selected pairs that exist in their sequence, in the
// order listed, and sequences left as they were when a selector fails.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <set>
#include <string>
#include <vector>

#include "slam/core/check.h"
#include "slam/features/eval/eval_pairs.h"
#include "slam/features/eval/image_sequence.h"

namespace {

void CheckMessage(const duskmap::Error& e, const std::string& origin) {
  const std::string message = e.what();
  if (message.rfind(origin, 0) != 0 || message.find('\n') != std::string::npos) std::abort();
}

std::vector<duskmap::ImageSequence> Sequences() {
  std::vector<duskmap::ImageSequence> sequences(2);
  sequences[0].name = "day";
  sequences[1].name = "dusk/cam";
  for (const int index : {1, 2, 3, 4}) {
    sequences[0].images.push_back({index, "day/img" + std::to_string(index)});
  }
  for (const int index : {1, 2, 7}) {
    sequences[1].images.push_back({index, "dusk/img" + std::to_string(index)});
  }
  for (duskmap::ImageSequence& sequence : sequences) {
    sequence.directory = "/nonexistent/" + sequence.name;
    sequence.layout = duskmap::SequenceLayout::kStatic;
    for (size_t i = 1; i < sequence.images.size(); ++i) {
      sequence.pairs.push_back({1, sequence.images[i].index, cv::Matx33d::eye()});
    }
  }
  return sequences;
}

bool SamePairs(const std::vector<duskmap::ImageSequence>& a, const std::vector<duskmap::ImageSequence>& b) {
  if (a.size() != b.size()) return false;
  for (size_t s = 0; s < a.size(); ++s) {
    if (a[s].name != b[s].name || a[s].pairs.size() != b[s].pairs.size()) return false;
    for (size_t p = 0; p < a[s].pairs.size(); ++p) {
      if (a[s].pairs[p].first_index != b[s].pairs[p].first_index ||
          a[s].pairs[p].second_index != b[s].pairs[p].second_index) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const bool spec = (data[0] & 1) != 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::string origin = spec ? "--pairs" : "fuzz.txt";
  std::vector<duskmap::PairSelector> selectors;
  try {
    selectors = spec ? duskmap::ParsePairList(text) : duskmap::ParsePairListText(text, "fuzz.txt");
  } catch (const duskmap::Error& e) {
    CheckMessage(e, origin);
    return 0;
  }
  if (selectors.empty()) std::abort();
  std::set<std::string> texts;
  for (const duskmap::PairSelector& selector : selectors) {
    if (selector.text.empty() || selector.origin.rfind(origin, 0) != 0) std::abort();
    for (const char edge : {selector.text.front(), selector.text.back()}) {
      if (edge == ' ' || edge == '\t' || edge == '\r' || edge == ',') std::abort();
    }
    if (!texts.insert(selector.text).second) std::abort();
    try {
      const duskmap::ImagePairSelector pair = duskmap::ParseImagePairSelector(selector);
      if (pair.first_index < 1 || pair.second_index < 1 || pair.first_index > 999999 ||
          pair.second_index > 999999 || pair.first_index == pair.second_index ||
          (selector.text.find('/') != std::string::npos) == pair.sequence.empty()) {
        std::abort();
      }
    } catch (const duskmap::Error& e) {
      CheckMessage(e, selector.origin);
    }
  }
  const std::vector<duskmap::ImageSequence> before = Sequences();
  std::vector<duskmap::ImageSequence> sequences = before;
  try {
    duskmap::SelectSequencePairs(selectors, &sequences);
  } catch (const duskmap::Error& e) {
    bool named = false;
    for (const duskmap::PairSelector& selector : selectors) {
      named = named || std::string(e.what()).rfind(selector.origin, 0) == 0;
    }
    if (!named || std::string(e.what()).find('\n') != std::string::npos) std::abort();
    if (!SamePairs(sequences, before)) std::abort();  // left as it was
    return 0;
  }
  for (const duskmap::ImageSequence& sequence : sequences) {
    if (sequence.pairs.empty()) std::abort();  // a sequence without a pair is dropped
    for (const duskmap::SequencePair& pair : sequence.pairs) {
      if (sequence.Image(pair.first_index) == nullptr || sequence.Image(pair.second_index) == nullptr ||
          pair.first_index == pair.second_index || pair.second_from_first != cv::Matx33d::eye()) {
        std::abort();
      }
    }
  }
  return 0;
}
