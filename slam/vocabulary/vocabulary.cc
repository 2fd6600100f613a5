#include "slam/vocabulary/vocabulary.h"

#include <algorithm>
#include <limits>

#include "slam/core/check.h"
#include "slam/core/timer.h"

namespace duskmap {
namespace {

// Temporary ids of words created earlier in the same frame: -2, -3, ...
WordId PendingId(size_t k) { return -static_cast<WordId>(k) - 2; }
size_t PendingIndex(WordId id) { return static_cast<size_t>(-id - 2); }

struct Candidate {
  WordId word;
  float distance;
};

// Merges the pending words (this frame's new words) into the two nearest
// candidates `best[0..*count)` (sorted; index results first on ties). Only a
// pending word closer than the current second candidate can matter, so
// distances stop early at that bound.
void MergePendingCandidates(DescriptorKind kind, BinaryDistance binary, int cols,
                            const uint8_t* row, const std::vector<const uint8_t*>& pending,
                            Candidate best[2], int* count) {
  for (size_t k = 0; k < pending.size(); ++k) {
    const float bound = *count < 2 ? std::numeric_limits<float>::infinity() : best[1].distance;
    const float d = DescriptorDistanceBounded(kind, row, pending[k], cols, bound, binary);
    if (!(d < bound)) continue;
    const Candidate c{PendingId(k), d};
    if (*count < 2) {
      best[(*count)++] = c;
    } else {
      best[1] = c;
    }
    if (*count == 2 && best[1].distance < best[0].distance) std::swap(best[0], best[1]);
  }
}

}  // namespace

void VocabularyOptions::Check() const {
  index.Check();
  SLAM_THROW_IF_NOT(ConfigError, nndr_ratio > 0.0 && nndr_ratio <= 1.0)
      << "VocabularyOptions.nndr_ratio must be in (0, 1], got " << nndr_ratio;
  SLAM_THROW_IF_NOT(ConfigError, max_features_per_node >= 0)
      << "VocabularyOptions.max_features_per_node must be >= 0, got " << max_features_per_node;
  SLAM_THROW_IF_NOT(ConfigError, bad_signature_ratio >= 0.0 && bad_signature_ratio <= 1.0)
      << "VocabularyOptions.bad_signature_ratio must be in [0, 1], got " << bad_signature_ratio;
}

int VocabularyOptions::MinFeatures() const {
  return static_cast<int>(bad_signature_ratio * max_features_per_node + 0.5);
}

std::vector<WordId> NodeQuantization::DistinctWords() const {
  std::vector<WordId> out;
  for (WordId w : words) {
    if (w > 0) out.push_back(w);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Vocabulary::Vocabulary(const VocabularyOptions& options) : options_(options) { options_.Check(); }
Vocabulary::~Vocabulary() = default;

void Vocabulary::CheckDescriptors(const cv::Mat& descriptors, DescriptorKind kind) const {
  if (descriptors.empty()) return;
  const int expected_type = kind == DescriptorKind::kFloat ? CV_32F : CV_8U;
  SLAM_THROW_IF_NOT(InputError, descriptors.type() == expected_type)
      << "Vocabulary: descriptors of type " << descriptors.type() << " do not match their kind ("
      << (kind == DescriptorKind::kFloat ? "float, CV_32F" : "binary, CV_8U") << ")";
  if (index_ == nullptr) return;
  SLAM_THROW_IF_NOT(InputError, kind == index_->kind() && descriptors.cols == index_->cols())
      << "Vocabulary: descriptors of width " << descriptors.cols
      << " differ from the vocabulary's (width " << index_->cols() << ", "
      << (index_->kind() == DescriptorKind::kFloat ? "float" : "binary") << ")";
}

NodeQuantization Vocabulary::Run(const cv::Mat& descriptors, DescriptorKind kind, bool create,
                                 std::vector<const uint8_t*>* new_rows) const {
  NodeQuantization q;
  q.num_features = descriptors.rows;
  const int limit = options_.max_features_per_node > 0
                        ? std::min(descriptors.rows, options_.max_features_per_node)
                        : descriptors.rows;
  q.words.assign(limit, kNoWord);
  if (descriptors.rows == 0 || descriptors.rows < options_.MinFeatures()) {
    q.bad_signature = true;
    return q;
  }
  const cv::Mat rows = descriptors.rowRange(0, limit).clone();  // contiguous
  const int cols = rows.cols;
  std::vector<std::vector<WordNeighbour>> nn;
  if (index_ != nullptr) index_->SearchTwoNearest(rows.ptr<uint8_t>(0), limit, &nn);
  std::vector<const uint8_t*> pending;
  for (int i = 0; i < limit; ++i) {
    const uint8_t* row = rows.ptr<uint8_t>(i);
    Candidate best[2] = {{kNoWord, 0.0f}, {kNoWord, 0.0f}};
    int count = 0;
    if (index_ != nullptr) {
      for (const WordNeighbour& n : nn[i]) best[count++] = {n.word, n.distance};  // sorted
    }
    if (options_.new_words_compared_together) {
      MergePendingCandidates(kind, options_.index.binary_distance, cols, row, pending, best, &count);
    }
    if (count >= 2 && best[0].distance <= options_.nndr_ratio * best[1].distance) {
      q.words[i] = best[0].word;
      if (best[0].word > 0) ++q.matched_words;
    } else {
      q.words[i] = PendingId(pending.size());
      pending.push_back(descriptors.ptr<uint8_t>(i));
    }
  }
  q.new_words = static_cast<int>(pending.size());
  for (WordId& w : q.words) {
    if (w < kNoWord) w = create ? next_word_id_ + static_cast<WordId>(PendingIndex(w)) : kNoWord;
  }
  if (new_rows != nullptr) *new_rows = std::move(pending);
  return q;
}

NodeQuantization Vocabulary::AddNode(NodeId node, const FrameFeatures& features) {
  return AddNode(node, features.descriptors, features.kind);
}

NodeQuantization Vocabulary::AddNode(NodeId node, const cv::Mat& descriptors, DescriptorKind kind) {
  Stopwatch watch;
  SLAM_THROW_IF_NOT(InputError, !inverted_.ContainsNode(node))
      << "Vocabulary: node " << node << " is already in the vocabulary";
  CheckDescriptors(descriptors, kind);
  std::vector<const uint8_t*> new_rows;
  NodeQuantization q = Run(descriptors, kind, /*create=*/true, &new_rows);
  SLAM_THROW_IF_NOT(InputError,
                    static_cast<int64_t>(next_word_id_) - 1 + static_cast<int64_t>(new_rows.size()) <=
                        kMaxWordId)
      << "Vocabulary: node " << node << " would create word " << next_word_id_ + new_rows.size() - 1
      << ", beyond the " << kMaxWordId << " words a vocabulary supports";
  if (!new_rows.empty() && index_ == nullptr) {
    index_ = std::make_unique<DescriptorIndex>(options_.index, kind, descriptors.cols);
  }
  for (size_t k = 0; k < new_rows.size(); ++k) {
    index_->Add(next_word_id_ + static_cast<WordId>(k), new_rows[k]);
  }
  next_word_id_ += static_cast<WordId>(new_rows.size());
  inverted_.AddNode(node, q.words, q.num_features);
  q.time_ms = watch.ElapsedMs();
  return q;
}

NodeQuantization Vocabulary::Quantize(const cv::Mat& descriptors, DescriptorKind kind) const {
  Stopwatch watch;
  CheckDescriptors(descriptors, kind);
  NodeQuantization q = Run(descriptors, kind, /*create=*/false, nullptr);
  q.time_ms = watch.ElapsedMs();
  return q;
}

NodeRemoval Vocabulary::RemoveNode(NodeId node) {
  NodeRemoval removal;
  std::optional<std::vector<WordId>> orphaned = inverted_.RemoveNode(node);
  if (!orphaned) return removal;
  removal.was_present = true;
  for (WordId w : *orphaned) {
    const bool removed = index_->Remove(w);
    SLAM_CHECK(removed);
  }
  removal.removed_words = std::move(*orphaned);
  return removal;
}

bool Vocabulary::ContainsWord(WordId word) const {
  return index_ != nullptr && index_->Contains(word);
}

WordRowFormat Vocabulary::stored_row_format() const {
  return index_ == nullptr ? WordRowFormat::kFloat32 : index_->format();
}

const uint8_t* Vocabulary::FindStoredRow(WordId word) const {
  return ContainsWord(word) ? index_->StoredRow(word) : nullptr;
}

size_t Vocabulary::num_words() const { return index_ == nullptr ? 0 : index_->size(); }
int Vocabulary::index_rebuilds() const { return index_ == nullptr ? 0 : index_->rebuild_count(); }

size_t Vocabulary::MemoryBytes() const {
  return (index_ == nullptr ? 0 : index_->MemoryBytes()) + inverted_.MemoryBytes();
}

void Vocabulary::RebuildIndex() {
  if (index_ != nullptr) index_->Rebuild();
}

}  // namespace duskmap
