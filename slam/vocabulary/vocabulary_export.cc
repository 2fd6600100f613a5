// Vocabulary::Export / Vocabulary::Import (declared in vocabulary.h); the
// snapshot's own members are in vocabulary_snapshot.cc.
#include <algorithm>
#include <unordered_set>

#include "slam/core/check.h"
#include "slam/core/timer.h"
#include "slam/vocabulary/vocabulary.h"

namespace duskmap {

std::vector<uint8_t> Vocabulary::SaveIndexState() const {
  return index_ != nullptr && index_->size() > 0 ? index_->SaveState() : std::vector<uint8_t>();
}

VocabularySnapshot Vocabulary::Export() const {
  VocabularySnapshot s;
  s.next_word_id = next_word_id_;
  s.float_storage = options_.index.float_storage;
  if (index_ != nullptr) {
    s.kind = index_->kind();
    s.float_storage = index_->format() == WordRowFormat::kQuantized8 ? DescriptorStorage::kUint8
                                                                     : DescriptorStorage::kFloat32;
  }
  for (NodeId node : inverted_.Nodes()) {
    VocabularyNodeWords n;
    n.node = node;
    n.num_features = inverted_.NodeFeatureCount(node);
    for (WordId w : inverted_.NodeWords(node)) {
      for (const WordReference& r : inverted_.References(w)) {
        if (r.node == node) n.word_counts.push_back({w, r.count});
      }
      s.word_ids.push_back(w);
    }
    s.nodes.push_back(std::move(n));
  }
  std::sort(s.word_ids.begin(), s.word_ids.end());
  s.word_ids.erase(std::unique(s.word_ids.begin(), s.word_ids.end()), s.word_ids.end());
  if (!s.word_ids.empty()) {
    const bool floats = index_->format() == WordRowFormat::kFloat32;
    const int width = floats ? index_->cols() : static_cast<int>(index_->stored_row_bytes());
    s.descriptors.create(static_cast<int>(s.word_ids.size()), width, floats ? CV_32F : CV_8U);
    for (size_t i = 0; i < s.word_ids.size(); ++i) {
      const uint8_t* row = index_->StoredRow(s.word_ids[i]);
      std::copy(row, row + index_->stored_row_bytes(),
                s.descriptors.ptr<uint8_t>(static_cast<int>(i)));
    }
  }
  return s;
}

namespace {

// The words' rows (as many as ids, of their format's type and width) and
// ids (positive, increasing, below the next id); InputError otherwise.
void CheckSnapshotWords(const VocabularySnapshot& s) {
  const WordRowFormat format = s.format();
  const int expected_type = format == WordRowFormat::kFloat32 ? CV_32F : CV_8U;
  SLAM_THROW_IF_NOT(InputError, s.descriptors.rows == static_cast<int>(s.word_ids.size()))
      << "vocabulary snapshot: " << s.descriptors.rows << " descriptor rows for "
      << s.word_ids.size() << " words";
  SLAM_THROW_IF_NOT(InputError, s.word_ids.empty() || s.descriptors.type() == expected_type)
      << "vocabulary snapshot: descriptors of type " << s.descriptors.type()
      << " do not match their kind ("
      << (format == WordRowFormat::kFloat32
              ? "float, CV_32F"
              : format == WordRowFormat::kQuantized8 ? "quantized float, CV_8U" : "binary, CV_8U")
      << ")";
  SLAM_THROW_IF_NOT(InputError, s.word_ids.empty() || s.DescriptorCols() > 0)
      << "vocabulary snapshot: stored rows of " << s.descriptors.cols
      << " bytes are too short for quantized words (8 bytes of scale, then the codes)";
  for (size_t i = 0; i < s.word_ids.size(); ++i) {
    SLAM_THROW_IF_NOT(InputError, s.word_ids[i] > 0 && (i == 0 || s.word_ids[i] > s.word_ids[i - 1]))
        << "vocabulary snapshot: word ids must be positive and strictly increasing (word "
        << s.word_ids[i] << " at position " << i << ")";
  }
  SLAM_THROW_IF_NOT(InputError, s.word_ids.empty() || s.next_word_id > s.word_ids.back())
      << "vocabulary snapshot: next word id " << s.next_word_id << " is not above the last word "
      << s.word_ids.back();
  SLAM_THROW_IF_NOT(InputError, s.next_word_id >= 1 && s.next_word_id <= kMaxWordId + 1)
      << "vocabulary snapshot: next word id " << s.next_word_id << " must be in [1, "
      << kMaxWordId + 1 << "]";
}

// The nodes (increasing, with word counts of snapshot words) and that every
// word is some node's; InputError otherwise.
void CheckSnapshotNodes(const VocabularySnapshot& s) {
  std::unordered_set<WordId> referenced;
  for (size_t i = 0; i < s.nodes.size(); ++i) {
    const VocabularyNodeWords& n = s.nodes[i];
    SLAM_THROW_IF_NOT(InputError, i == 0 || n.node > s.nodes[i - 1].node)
        << "vocabulary snapshot: node ids must be strictly increasing (node " << n.node << ")";
    SLAM_THROW_IF_NOT(InputError, n.num_features >= 0)
        << "vocabulary snapshot: node " << n.node << " has " << n.num_features << " features";
    for (size_t k = 0; k < n.word_counts.size(); ++k) {
      const auto& [w, count] = n.word_counts[k];
      SLAM_THROW_IF_NOT(InputError, std::binary_search(s.word_ids.begin(), s.word_ids.end(), w))
          << "vocabulary snapshot: node " << n.node << " references word " << w
          << ", which is not in the snapshot";
      SLAM_THROW_IF_NOT(InputError, count >= 1 && (k == 0 || w > n.word_counts[k - 1].first))
          << "vocabulary snapshot: node " << n.node << " word " << w
          << ": words must be increasing with counts >= 1 (count " << count << ")";
      referenced.insert(w);
    }
  }
  SLAM_THROW_IF_NOT(InputError, referenced.size() == s.word_ids.size())
      << "vocabulary snapshot: " << s.word_ids.size() - referenced.size()
      << " words are referenced by no node";
}

}  // namespace

void Vocabulary::Import(const VocabularySnapshot& s) {
  SLAM_THROW_IF_NOT(InputError, num_nodes() == 0 && num_words() == 0 && next_word_id_ == 1)
      << "Vocabulary::Import: the vocabulary is not empty (" << num_nodes() << " nodes, "
      << num_words() << " words)";
  CheckSnapshotWords(s);
  CheckSnapshotNodes(s);

  if (!s.word_ids.empty()) {
    // The words are kept as the snapshot stores them, whatever this
    // vocabulary's options say (a map decides how its words are stored).
    DescriptorIndexOptions index_options = options_.index;
    index_options.float_storage = s.float_storage;
    Stopwatch watch;
    index_ = std::make_unique<DescriptorIndex>(index_options, s.kind, s.DescriptorCols());
    const cv::Mat rows = s.descriptors.isContinuous() ? s.descriptors : s.descriptors.clone();
    std::string problem = s.index_state_problem;
    if (problem.empty() && s.index_state.empty()) problem = "no stored index";
    if (problem.empty() &&
        index_->RestoreState(s.index_state, s.word_ids, rows.ptr<uint8_t>(0), &problem)) {
      index_restore_.restored = true;
    } else {
      index_restore_.rebuild_reason = problem;
      // A fresh index, whatever a failed restore left behind.
      index_ = std::make_unique<DescriptorIndex>(index_options, s.kind, s.DescriptorCols());
      index_->ReserveIds(s.word_ids.back());
      for (size_t i = 0; i < s.word_ids.size(); ++i) {
        index_->AddStored(s.word_ids[i], rows.ptr<uint8_t>(static_cast<int>(i)));
      }
      index_->Rebuild();
      // An imported vocabulary is searched far more than it grows (not at all
      // when localizing): its index keeps no room for growth.
      index_->Compact();
    }
    index_restore_.seconds = watch.ElapsedMs() / 1000.0;
    inverted_.ReserveWords(s.word_ids.back());
  }
  for (const VocabularyNodeWords& n : s.nodes) {
    std::vector<WordId> words;
    for (const auto& [w, count] : n.word_counts) words.insert(words.end(), count, w);
    inverted_.AddNode(n.node, words, n.num_features);
  }
  inverted_.ShrinkToFit();
  next_word_id_ = s.next_word_id;
}

}  // namespace duskmap
