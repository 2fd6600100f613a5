// The ids of the report's tables (ReportTable::id), for code that reads a
// built report back: the agreement with the paper, tests.
#pragma once

namespace duskmap {

inline constexpr char kTableRelocalizationPct[] = "relocalization_pct";
inline constexpr char kTableInliersPct[] = "inliers_pct";
inline constexpr char kTableJumpsMm[] = "jumps_mm";
inline constexpr char kTableCorrectPct[] = "correct_pct";
inline constexpr char kTableWrongCount[] = "wrong_count";
inline constexpr char kTableNoCandidatePct[] = "no_candidate_pct";
inline constexpr char kTableGroundTruthThresholds[] = "ground_truth_thresholds";
inline constexpr char kTableGraphNodes[] = "graph_nodes";
inline constexpr char kTableMemoryMb[] = "memory_mb";
inline constexpr char kTableMemoryPerNodeKib[] = "memory_per_node_kib";
inline constexpr char kTableAteMm[] = "ate_mm";
inline constexpr char kTableGraphReduction[] = "graph_reduction";
inline constexpr char kTableTiming[] = "timing";
inline constexpr char kTableTimingBudget[] = "timing_budget";
inline constexpr char kTableConsecutiveMaxGapM[] = "consecutive_max_gap_m";
inline constexpr char kTableConsecutiveWithin55cmPct[] = "consecutive_within_55cm_pct";
inline constexpr char kTableConsecutiveWithin55cmBoundPct[] = "consecutive_within_55cm_bound_pct";
// The scaling curve (scaling_tables.h), with a config's "scaling" only.
inline constexpr char kTableScalingNodes[] = "scaling_nodes";
inline constexpr char kTableScalingLcdTeMs[] = "scaling_lcd_te_ms";
inline constexpr char kTableScalingMemoryMb[] = "scaling_memory_mb";
inline constexpr char kTableScalingMapOpenS[] = "scaling_map_open_s";
inline constexpr char kTableScalingRelocalizationPct[] = "scaling_relocalization_pct";
inline constexpr char kTableScalingCorrectPct[] = "scaling_correct_pct";

// Rows of the timing table read back.
inline constexpr char kRowFeatureDetectionMs[] = "feature_detection_ms";
inline constexpr char kRowLcdSingleSessionMs[] = "lcd_single_session_ms";
inline constexpr char kRowLcdFullMergeMs[] = "lcd_1+2+3+4+5+6_ms";
inline constexpr char kRowTeMs[] = "te_ms";
inline constexpr char kRowFeaturesPerFrame[] = "features_per_frame";

}  // namespace duskmap
