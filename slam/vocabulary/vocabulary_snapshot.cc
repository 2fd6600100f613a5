#include "slam/vocabulary/vocabulary_snapshot.h"

namespace duskmap {

int VocabularySnapshot::DescriptorCols() const {
  if (descriptors.empty()) return 0;
  return format() == WordRowFormat::kQuantized8
             ? descriptors.cols - static_cast<int>(WordRowBytes(WordRowFormat::kQuantized8, 0))
             : descriptors.cols;
}

bool VocabularySnapshot::operator==(const VocabularySnapshot& other) const {
  if (kind != other.kind || format() != other.format() || word_ids != other.word_ids ||
      next_word_id != other.next_word_id ||
      descriptors.rows != other.descriptors.rows || nodes.size() != other.nodes.size()) {
    return false;
  }
  if (!descriptors.empty() &&
      (descriptors.type() != other.descriptors.type() || descriptors.cols != other.descriptors.cols ||
       cv::norm(descriptors, other.descriptors, cv::NORM_INF) != 0.0)) {
    return false;
  }
  for (size_t i = 0; i < nodes.size(); ++i) {
    const VocabularyNodeWords& a = nodes[i];
    const VocabularyNodeWords& b = other.nodes[i];
    if (a.node != b.node || a.num_features != b.num_features || a.word_counts != b.word_counts) return false;
  }
  return true;
}

}  // namespace duskmap
