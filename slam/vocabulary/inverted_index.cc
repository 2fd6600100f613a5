#include "slam/vocabulary/inverted_index.h"

#include <algorithm>
#include <map>

#include "slam/core/check.h"

namespace duskmap {
namespace {
const std::vector<WordId> kNoWords;
const ReferenceList kNoReferences;
// What glibc's malloc adds to a block on average (an 8-byte header, sizes
// rounded up to 16): counted for every separate heap block.
constexpr size_t kMallocOverhead = 16;
}  // namespace

ReferenceList::ReferenceList(ReferenceList&& other) noexcept : inline_() { TakeFrom(&other); }

ReferenceList& ReferenceList::operator=(ReferenceList&& other) noexcept {
  if (this == &other) return *this;
  Release();
  TakeFrom(&other);
  return *this;
}

void ReferenceList::TakeFrom(ReferenceList* other) {
  size_ = other->size_;
  capacity_ = other->capacity_;
  if (other->on_heap()) {
    heap_ = other->heap_;
  } else {
    inline_ = other->inline_;
  }
  other->inline_ = WordReference();  // the heap block (if any) is ours now
  other->size_ = 0;
  other->capacity_ = 1;
}

void ReferenceList::Release() {
  if (on_heap()) delete[] heap_;
  inline_ = WordReference();
  size_ = 0;
  capacity_ = 1;
}

void ReferenceList::PushBack(const WordReference& reference) {
  if (size_ == capacity_) {
    const uint32_t capacity = 2 * capacity_;
    WordReference* grown = new WordReference[capacity];
    std::copy(begin(), end(), grown);
    if (on_heap()) delete[] heap_;
    heap_ = grown;
    capacity_ = capacity;
  }
  data()[size_++] = reference;
}

bool ReferenceList::Erase(NodeId node) {
  WordReference* first = data();
  WordReference* last = first + size_;
  WordReference* pos =
      std::find_if(first, last, [node](const WordReference& r) { return r.node == node; });
  if (pos == last) return false;
  std::copy(pos + 1, last, pos);
  --size_;
  if (size_ <= 1 && on_heap()) {  // back inline
    WordReference* block = heap_;
    inline_ = size_ == 1 ? block[0] : WordReference();
    delete[] block;
    capacity_ = 1;
  }
  return true;
}

void ReferenceList::ShrinkToFit() {
  if (!on_heap() || capacity_ == size_) return;  // size_ >= 2 on the heap
  WordReference* exact = new WordReference[size_];
  std::copy(begin(), end(), exact);
  delete[] heap_;
  heap_ = exact;
  capacity_ = size_;
}

size_t ReferenceList::HeapBytes() const {
  return on_heap() ? capacity_ * sizeof(WordReference) + kMallocOverhead : 0;
}

void InvertedIndex::AddNode(NodeId node, const std::vector<WordId>& words, int num_features) {
  SLAM_THROW_IF_NOT(InputError, !ContainsNode(node))
      << "InvertedIndex: node " << node << " is already in the vocabulary";
  SLAM_THROW_IF_NOT(InputError, num_features >= 0)
      << "InvertedIndex: node " << node << " has a negative feature count";
  std::map<WordId, int32_t> counts;
  for (WordId w : words) {
    if (w > 0) ++counts[w];
  }
  NodeEntry entry;
  entry.num_features = std::max<int>(num_features, static_cast<int>(words.size()));
  const float inverse = entry.num_features > 0 ? 1.0f / entry.num_features : 0.0f;
  entry.distinct_words.reserve(counts.size());
  for (const auto& [word, count] : counts) {
    entry.distinct_words.push_back(word);
    uint32_t pos = word_slots_.Find(word);
    if (pos == WordSlots::kNone) {
      pos = static_cast<uint32_t>(lists_.size());
      lists_.emplace_back();
      list_words_.push_back(word);
      word_slots_.Set(word, pos);
    }
    lists_[pos].PushBack({node, count, inverse});
  }
  nodes_.emplace(node, std::move(entry));
}

std::optional<std::vector<WordId>> InvertedIndex::RemoveNode(NodeId node) {
  auto it = nodes_.find(node);
  if (it == nodes_.end()) return std::nullopt;
  std::vector<WordId> orphaned;
  for (WordId w : it->second.distinct_words) {
    const uint32_t pos = word_slots_.Find(w);
    SLAM_CHECK(pos != WordSlots::kNone);
    SLAM_CHECK(lists_[pos].Erase(node));
    if (lists_[pos].empty()) {
      // The last list takes the freed position.
      const uint32_t last = static_cast<uint32_t>(lists_.size() - 1);
      if (pos != last) {
        lists_[pos] = std::move(lists_[last]);
        list_words_[pos] = list_words_[last];
        word_slots_.Set(list_words_[pos], pos);
      }
      lists_.pop_back();
      list_words_.pop_back();
      word_slots_.Erase(w);
      orphaned.push_back(w);
    }
  }
  nodes_.erase(it);
  return orphaned;  // distinct_words was sorted, so is this
}

const ReferenceList& InvertedIndex::References(WordId word) const {
  const uint32_t pos = word_slots_.Find(word);
  return pos == WordSlots::kNone ? kNoReferences : lists_[pos];
}

const std::vector<WordId>& InvertedIndex::NodeWords(NodeId node) const {
  auto it = nodes_.find(node);
  return it == nodes_.end() ? kNoWords : it->second.distinct_words;
}

int InvertedIndex::NodeFeatureCount(NodeId node) const {
  auto it = nodes_.find(node);
  return it == nodes_.end() ? 0 : it->second.num_features;
}

std::vector<NodeId> InvertedIndex::Nodes() const {
  std::vector<NodeId> ids;
  ids.reserve(nodes_.size());
  for (const auto& [id, entry] : nodes_) ids.push_back(id);
  std::sort(ids.begin(), ids.end());
  return ids;
}

void InvertedIndex::ShrinkToFit() {
  for (ReferenceList& list : lists_) list.ShrinkToFit();
  lists_.shrink_to_fit();
  list_words_.shrink_to_fit();
  word_slots_.Pack();
}

size_t InvertedIndex::MemoryBytes() const {
  size_t bytes = word_slots_.MemoryBytes() + lists_.capacity() * sizeof(ReferenceList) +
                 list_words_.capacity() * sizeof(WordId) + 3 * kMallocOverhead;
  for (const ReferenceList& list : lists_) bytes += list.HeapBytes();
  // Node entries: a hash node (next pointer, key, value) per node, buckets,
  // and the node's word vector.
  bytes += nodes_.bucket_count() * sizeof(void*);
  for (const auto& [n, entry] : nodes_) {
    bytes += sizeof(void*) + sizeof(n) + sizeof(entry) + kMallocOverhead +
             entry.distinct_words.capacity() * sizeof(WordId) + kMallocOverhead;
  }
  return bytes;
}

}  // namespace duskmap
