// JSON codecs of the vocabulary's options (slam/core/json_codec.h).
#pragma once

#include <utility>

#include "slam/core/json_codec.h"
#include "slam/features/feature_options_json.h"
#include "slam/vocabulary/descriptor_index.h"
#include "slam/vocabulary/vocabulary.h"

namespace duskmap {

template <>
struct JsonEnumNames<IndexKind> {
  static constexpr std::pair<IndexKind, const char*> kNames[] = {
      {IndexKind::kKdTree, "kdtree"},
      {IndexKind::kBitKdTree, "bit_kdtree"},
      {IndexKind::kLsh, "lsh"},
      {IndexKind::kHierarchical, "hierarchical"},
      {IndexKind::kLinear, "linear"}};
};

template <>
struct JsonCodec<DescriptorIndexOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("float_kind", o.float_kind);
    f("binary_kind", o.binary_kind);
    f("kd_trees", o.kd_trees);
    f("kd_leaf_size", o.kd_leaf_size);
    f("checks", o.checks);
    f("rebalancing_factor", o.rebalancing_factor);
    f("lsh_tables", o.lsh_tables);
    f("lsh_key_bits", o.lsh_key_bits);
    f("lsh_multi_probe", o.lsh_multi_probe);
    f("hierarchical_branching", o.hierarchical_branching);
    f("hierarchical_trees", o.hierarchical_trees);
    f("hierarchical_leaf_size", o.hierarchical_leaf_size);
    f("seed", o.seed);
    f("float_storage", o.float_storage);
    f("binary_distance", o.binary_distance);
  }
};

template <>
struct JsonCodec<VocabularyOptions> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("index", o.index);
    f("nndr_ratio", o.nndr_ratio);
    f("max_features_per_node", o.max_features_per_node);
    f("bad_signature_ratio", o.bad_signature_ratio);
    f("new_words_compared_together", o.new_words_compared_together);
  }
};

}  // namespace duskmap
