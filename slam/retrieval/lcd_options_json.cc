#include "slam/retrieval/lcd_options_json.h"

namespace duskmap {
namespace {

void ReadIndex(JsonFields f, DescriptorIndexOptions* o) {
  std::string float_kind = IndexKindName(o->float_kind);
  std::string binary_kind = IndexKindName(o->binary_kind);
  f.Read("float_kind", &float_kind);
  f.Read("binary_kind", &binary_kind);
  try {
    o->float_kind = ParseIndexKind(float_kind);
    o->binary_kind = ParseIndexKind(binary_kind);
  } catch (const ConfigError& e) {
    SLAM_THROW(ConfigError) << f.where() << ": " << e.what();
  }
  f.Read("kd_trees", &o->kd_trees);
  f.Read("kd_leaf_size", &o->kd_leaf_size);
  f.Read("checks", &o->checks);
  f.Read("rebalancing_factor", &o->rebalancing_factor);
  f.Read("lsh_tables", &o->lsh_tables);
  f.Read("lsh_key_bits", &o->lsh_key_bits);
  f.Read("lsh_multi_probe", &o->lsh_multi_probe);
  f.Read("hierarchical_branching", &o->hierarchical_branching);
  f.Read("hierarchical_trees", &o->hierarchical_trees);
  f.Read("hierarchical_leaf_size", &o->hierarchical_leaf_size);
  f.Read("seed", &o->seed);
  f.RejectUnknown();
}

void ReadVocabulary(JsonFields f, VocabularyOptions* o) {
  ReadIndex(f.Child("index"), &o->index);
  f.Read("nndr_ratio", &o->nndr_ratio);
  f.Read("max_features_per_node", &o->max_features_per_node);
  f.Read("bad_signature_ratio", &o->bad_signature_ratio);
  f.Read("new_words_compared_together", &o->new_words_compared_together);
  f.RejectUnknown();
}

void ReadBayes(JsonFields f, BayesFilterOptions* o) {
  f.Read("prediction", &o->prediction);
  f.Read("virtual_place_prior", &o->virtual_place_prior);
  f.RejectUnknown();
}

}  // namespace

LoopClosureOptions ReadLoopClosureOptions(const nlohmann::json& object, const std::string& where) {
  JsonFields f(object, where);
  LoopClosureOptions o;
  ReadVocabulary(f.Child("vocabulary"), &o.vocabulary);
  ReadBayes(f.Child("bayes"), &o.bayes);
  f.Read("loop_threshold", &o.loop_threshold);
  f.Read("aggressive_loop_threshold", &o.aggressive_loop_threshold);
  f.Read("loop_ratio", &o.loop_ratio);
  f.Read("short_term_memory_size", &o.short_term_memory_size);
  f.Read("top_hypotheses", &o.top_hypotheses);
  f.RejectUnknown();
  try {
    o.Check();
  } catch (const ConfigError& e) {
    SLAM_THROW(ConfigError) << where << ": " << e.what();
  }
  return o;
}

ProximityOptions ReadProximityOptions(const nlohmann::json& object, const std::string& where) {
  JsonFields f(object, where);
  ProximityOptions o;
  f.Read("local_radius_m", &o.local_radius_m);
  f.Read("max_angle_deg", &o.max_angle_deg);
  f.Read("max_paths", &o.max_paths);
  f.Read("path_filtering_radius_m", &o.path_filtering_radius_m);
  f.Read("max_path_depth", &o.max_path_depth);
  if (f.Has("forward_axis")) {
    std::vector<double> axis;
    f.Read("forward_axis", &axis);
    SLAM_THROW_IF_NOT(ConfigError, axis.size() == 3)
        << where << ".forward_axis: expected 3 numbers, got " << axis.size();
    o.forward_axis = Eigen::Vector3d(axis[0], axis[1], axis[2]);
  }
  f.RejectUnknown();
  try {
    o.Check();
  } catch (const ConfigError& e) {
    SLAM_THROW(ConfigError) << where << ": " << e.what();
  }
  return o;
}

}  // namespace duskmap
