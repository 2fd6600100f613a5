#include "slam/report/agreement.h"

#include <map>

#include <gtest/gtest.h>

#include "slam/report/report_table_ids.h"

namespace duskmap {
namespace {

const std::vector<std::string> kRows = {"1", "2", "3", "1+2+3", "1-2-3", "1|2|3"};
const std::vector<std::string> kFeatures = {"SU", "SI", "BK", "OR"};

// A hand-made re-localization table: measured = paper + a known offset.
// Paper values per feature (rows 1, 2, 3, 1+2+3, 1-2-3, 1|2|3).
ReportTable Relocalization() {
  ReportTable table(kTableRelocalizationPct, "Re-localization (%)", kRows, kFeatures);
  const std::map<std::string, std::vector<double>> paper = {{"SU", {70, 80, 75, 95, 90, 92}},
                                                            {"SI", {65, 75, 72, 93, 88, 90}},
                                                            {"BK", {60, 68, 66, 90, 85, 86}}};
  // Single maps: SU -10 on each, SI +5, BK -2 (MAD 17/3 over 9 cells);
  // multi-session: all 0 except SU 1|2|3 -6.
  const std::map<std::string, std::vector<double>> measured = {{"SU", {60, 70, 65, 95, 90, 86}},
                                                               {"SI", {70, 80, 77, 93, 88, 90}},
                                                               {"BK", {58, 66, 64, 90, 85, 86}}};
  for (const auto& [feature, values] : paper) {
    for (size_t i = 0; i < kRows.size(); ++i) {
      table.SetPaper(kRows[i], feature, values[i]);
      table.SetMeasured(kRows[i], feature, measured.at(feature)[i]);
    }
  }
  for (const std::string& row : kRows) table.SetMeasured(row, "OR", 50);  // no paper value
  return table;
}

PaperReference Paper(std::vector<std::string> findings) {
  return PaperReference(nlohmann::json{{"qualitative_findings", findings}});
}

SingleMapMatrix Matrix(bool diagonal_best) {
  SingleMapMatrix matrix;
  matrix.map_rows = {"1", "2", "3"};
  matrix.sessions = {"A", "B", "C"};
  matrix.closest_row = {"1", "2", "3"};
  for (const char* feature : {"SU", "SI", "BK"}) {
    auto& pct = matrix.pct[feature];
    pct.assign(3, std::vector<std::optional<double>>(3));
    for (int r = 0; r < 3; ++r) {
      for (int s = 0; s < 3; ++s) pct[r][s] = 80.0 - 20.0 * std::abs(r - s);
    }
    if (!diagonal_best) pct[1][1] = 10.0;  // map 2 worst on its own session
  }
  return matrix;
}

TEST(SpearmanRho, MatchesHandComputedValues) {
  EXPECT_NEAR(*SpearmanRho({1, 2, 3, 4}, {1, 3, 2, 4}), 0.8, 1e-12);
  EXPECT_NEAR(*SpearmanRho({10, 20, 30}, {3, 2, 1}), -1.0, 1e-12);
  // Ties take average ranks: (1.5, 1.5, 3) against (1, 2, 3).
  EXPECT_NEAR(*SpearmanRho({1, 1, 2}, {1, 2, 3}), 1.5 / std::sqrt(3.0), 1e-12);
  EXPECT_FALSE(SpearmanRho({1, 2}, {1, 2}).has_value());
  EXPECT_FALSE(SpearmanRho({1, 1, 1}, {1, 2, 3}).has_value());
  EXPECT_FALSE(SpearmanRho({1, 2, 3}, {1, 2}).has_value());
}

TEST(SpearmanRhoRange, LetsOnlyCloseValuesTradePlaces) {
  // Measured order c > b > a gives rho 0.5 against the reference's c > a > b;
  // a and b lie 0.5 apart, so with a resolution of 1 they may swap (rho 1).
  const std::vector<double> measured = {10.0, 10.5, 20.0};
  const std::vector<double> reference = {2.0, 1.0, 3.0};
  auto range = SpearmanRhoRange(measured, reference, 1.0);
  ASSERT_TRUE(range.has_value());
  EXPECT_NEAR(range->first, 0.5, 1e-12);
  EXPECT_NEAR(range->second, 1.0, 1e-12);
  range = SpearmanRhoRange(measured, reference, 0.4);  // nothing that close: the one order
  ASSERT_TRUE(range.has_value());
  EXPECT_NEAR(range->first, 0.5, 1e-12);
  EXPECT_NEAR(range->second, 0.5, 1e-12);
  range = SpearmanRhoRange(measured, reference, 100.0);  // every order, the reversed one too
  ASSERT_TRUE(range.has_value());
  EXPECT_NEAR(range->first, -1.0, 1e-12);
  EXPECT_NEAR(range->second, 1.0, 1e-12);
  // A tie is two orders; the average-rank rho (0.87) lies between them.
  range = SpearmanRhoRange({1.0, 1.0, 2.0}, {1.0, 2.0, 3.0}, 0.5);
  ASSERT_TRUE(range.has_value());
  EXPECT_NEAR(range->first, 0.5, 1e-12);
  EXPECT_NEAR(range->second, 1.0, 1e-12);
  EXPECT_FALSE(SpearmanRhoRange({1, 2}, {1, 2}, 1.0).has_value());
  const std::vector<double> ten = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  EXPECT_FALSE(SpearmanRhoRange(ten, ten, 1.0).has_value());  // above kMaxFeaturesForRhoRange
}

TEST(ComputeAgreement, DeviationPerTablePartAndRole) {
  const AgreementReport agreement = ComputeAgreement({Relocalization()}, Matrix(true), Paper({}));
  const TableDeviation* single = agreement.FindDeviation(kDeviationSingleMaps);
  ASSERT_NE(single, nullptr);
  EXPECT_EQ(single->cells, 9);  // OR has no paper value
  EXPECT_NEAR(*single->mean_abs_deviation, (3 * 10 + 3 * 5 + 3 * 2) / 9.0, 1e-12);
  EXPECT_DOUBLE_EQ(*single->max_abs_deviation, 10.0);
  EXPECT_EQ(single->worst_cell, "SU on 1: 60 (paper 70)");
  EXPECT_EQ(single->role, AgreementRole::kCalibration);
  const TableDeviation* multi = agreement.FindDeviation(kDeviationMultiMaps);
  ASSERT_NE(multi, nullptr);
  EXPECT_EQ(multi->cells, 9);
  EXPECT_NEAR(*multi->mean_abs_deviation, 6.0 / 9.0, 1e-12);
  EXPECT_EQ(multi->role, AgreementRole::kHeldOut);
  // Tables the report lacks leave their entries empty, not zero.
  const TableDeviation* inliers = agreement.FindDeviation(kDeviationInliers);
  ASSERT_NE(inliers, nullptr);
  EXPECT_EQ(inliers->cells, 0);
  EXPECT_FALSE(inliers->mean_abs_deviation.has_value());
}

TEST(ComputeAgreement, RankingAndNightMinusDay) {
  const AgreementReport agreement = ComputeAgreement({Relocalization()}, Matrix(true), Paper({}));
  const RankAgreement& ranking = agreement.ranking;
  ASSERT_EQ(ranking.features, (std::vector<std::string>{"SU", "SI", "BK"}));
  EXPECT_NEAR(ranking.measured_mean_pct[0], 65.0, 1e-12);
  EXPECT_NEAR(ranking.paper_mean_pct[0], 75.0, 1e-12);
  // Measured order SI > SU > BK, the paper's SU > SI > BK: rho = 1 - 6*2/24.
  EXPECT_NEAR(*ranking.spearman_rho, 0.5, 1e-12);
  // No two features within kRankResolutionPts (65, 75.7, 62.7): the one order.
  EXPECT_TRUE(ranking.close_pairs.empty());
  EXPECT_NEAR(*ranking.spearman_rho_low, 0.5, 1e-12);
  EXPECT_NEAR(*ranking.spearman_rho_high, 0.5, 1e-12);
  // Map 3 - map 1: measured (5 + 7 + 6) / 3, paper (5 + 7 + 6) / 3.
  EXPECT_EQ(agreement.night_minus_day.night_row, "3");
  EXPECT_EQ(agreement.night_minus_day.day_row, "1");
  EXPECT_NEAR(*agreement.night_minus_day.measured_pts, 6.0, 1e-12);
  EXPECT_NEAR(*agreement.night_minus_day.paper_pts, 6.0, 1e-12);
}

TEST(ComputeAgreement, SignedDeviationPerSingleSessionMap) {
  ReportTable table = Relocalization();
  table.SetMeasured("2", "SU", 90);  // paper 80: map 2 is now +10, +5, -2
  table.SetMeasured("3", "SI", 80);  // paper 72: map 3 is -10, +8, -2
  const AgreementReport agreement = ComputeAgreement({table}, Matrix(true), Paper({}));
  ASSERT_EQ(agreement.single_map_rows.size(), 3u);  // the multi-session rows are not single maps
  EXPECT_EQ(agreement.single_map_rows[0].row, "1");
  EXPECT_NEAR(*agreement.single_map_rows[0].mean_pts, (-10.0 + 5.0 - 2.0) / 3.0, 1e-12);
  EXPECT_EQ(agreement.single_map_rows[0].features, 3);
  EXPECT_NEAR(*agreement.single_map_rows[1].mean_pts, (10.0 + 5.0 - 2.0) / 3.0, 1e-12);
  EXPECT_EQ(agreement.single_map_rows[2].features, 3);  // OR has no paper values: not ranked
  EXPECT_NEAR(*agreement.single_map_rows[2].mean_pts, (-10.0 + 8.0 - 2.0) / 3.0, 1e-12);
  const std::string markdown = AgreementToMarkdown(agreement);
  EXPECT_NE(markdown.find("signed deviation per map** (measured − paper, cumulative re-localization, mean "
                          "over the ranked features, points): 1 -2.3 2 +4.3 3 -1.3\n"),
            std::string::npos)
      << markdown;
  const nlohmann::json json = AgreementToJson(agreement);
  EXPECT_EQ(json["single_map_rows"][1]["row"], "2");
  EXPECT_NEAR(json["single_map_rows"][1]["mean_signed_deviation_pts"].get<double>(), 13.0 / 3.0, 1e-12);
}

TEST(ComputeAgreement, FeaturesPerFrameRatio) {
  ReportTable timing(kTableTiming, "timing", {kRowFeaturesPerFrame}, kFeatures, 1);
  timing.SetMeasured(kRowFeaturesPerFrame, "SU", 423.5);
  timing.SetPaper(kRowFeaturesPerFrame, "SU", 847);
  timing.SetMeasured(kRowFeaturesPerFrame, "OR", 1000);  // no paper value: no ratio
  const AgreementReport agreement = ComputeAgreement({timing}, Matrix(true), Paper({}));
  ASSERT_EQ(agreement.features_per_frame.size(), 1u);
  EXPECT_EQ(agreement.features_per_frame[0].feature, "SU");
  EXPECT_DOUBLE_EQ(agreement.features_per_frame[0].ratio, 0.5);
}

TEST(ComputeAgreement, FindingsDecidedByTheirRules) {
  const std::vector<std::string> findings = {
      "Single-session maps: re-localization is best on the diagonal (...)",
      "SuperPoint (with or without SuperGlue) is the most robust to illumination change; ...",
      "Merging more sessions with different illumination raises re-localization ...",
      "A finding no number decides."};
  ReportTable wrong(kTableWrongCount, "wrong", kRows, kFeatures);
  for (const std::string& row : kRows) {
    for (const std::string& feature : kFeatures) wrong.SetMeasured(row, feature, 0);
  }
  AgreementReport agreement =
      ComputeAgreement({Relocalization(), wrong}, Matrix(true), Paper(findings));
  ASSERT_EQ(agreement.findings.size(), 4u);
  EXPECT_EQ(agreement.findings[0].verdict, FindingVerdict::kReproduced)
      << agreement.findings[0].measured;
  EXPECT_NE(agreement.findings[0].measured.find("9/9"), std::string::npos);
  // BK has the lowest single-map mean on both sides.
  EXPECT_EQ(agreement.findings[1].verdict, FindingVerdict::kReproduced)
      << agreement.findings[1].measured;
  EXPECT_EQ(agreement.findings[1].paper.rfind("holds", 0), 0u) << agreement.findings[1].paper;
  // Each 1+2+3 is above its single maps and the best row; 1-2-3 trails it by
  // 5 points: reproduced.
  EXPECT_EQ(agreement.findings[2].verdict, FindingVerdict::kReproduced)
      << agreement.findings[2].measured;
  EXPECT_EQ(agreement.findings[3].verdict, FindingVerdict::kNotDecided);
  EXPECT_TRUE(agreement.findings[3].criterion.empty());
  EXPECT_EQ(agreement.FindingsReproduced(), 3);
  EXPECT_EQ(agreement.FindingsDecided(), 3);

  // Off the diagonal, and a merge below one of its single maps: not reproduced.
  ReportTable relocalization = Relocalization();
  relocalization.SetMeasured("1+2+3", "SI", 79);  // below map 2's 80
  agreement = ComputeAgreement({relocalization}, Matrix(false), Paper(findings));
  EXPECT_EQ(agreement.findings[0].verdict, FindingVerdict::kNotReproduced);
  EXPECT_EQ(agreement.findings[2].verdict, FindingVerdict::kNotReproduced);
  EXPECT_NE(agreement.findings[2].measured.find("2/3"), std::string::npos)
      << agreement.findings[2].measured;
}

// DN (duskmap's learned descriptor, FeatureType::learned) is the learned
// feature of the robustness finding: it must have the highest single-map mean
// when it ran, and is never the "lowest hand-crafted" one.
TEST(ComputeAgreement, DuskNetIsTheLearnedFeatureOfTheRobustnessFinding) {
  const std::vector<std::string> findings = {
      "SuperPoint (with or without SuperGlue) is the most robust to illumination change; ..."};
  const std::vector<std::string> features = {"SU", "SI", "BK", "DN"};
  auto table = [&](double dn_pct) {
    ReportTable t(kTableRelocalizationPct, "Re-localization (%)", kRows, features);
    const std::map<std::string, double> pct = {{"SU", 70}, {"SI", 75}, {"BK", 60}, {"DN", dn_pct}};
    for (const std::string& row : kRows) {
      for (const auto& [feature, value] : pct) {
        t.SetMeasured(row, feature, value);
        if (feature != "DN") t.SetPaper(row, feature, value);  // the paper has no DN column
      }
    }
    return t;
  };
  AgreementReport agreement = ComputeAgreement({table(80)}, Matrix(true), Paper(findings));
  ASSERT_EQ(agreement.findings.size(), 1u);
  EXPECT_EQ(agreement.findings[0].verdict, FindingVerdict::kReproduced)
      << agreement.findings[0].measured;
  EXPECT_NE(agreement.findings[0].measured.find("highest: DN 80.0"), std::string::npos)
      << agreement.findings[0].measured;
  // DN below SIFT: a hand-crafted feature is the most robust.
  agreement = ComputeAgreement({table(72)}, Matrix(true), Paper(findings));
  EXPECT_EQ(agreement.findings[0].verdict, FindingVerdict::kNotReproduced)
      << agreement.findings[0].measured;
  EXPECT_NE(agreement.findings[0].measured.find("highest: SI 75.0 %; best learned: DN 72.0 %"),
            std::string::npos)
      << agreement.findings[0].measured;
  // DN lowest of all: still not the "lowest hand-crafted" feature (BK is).
  agreement = ComputeAgreement({table(50)}, Matrix(true), Paper(findings));
  EXPECT_NE(agreement.findings[0].measured.find("lowest hand-crafted single-map mean: BK"),
            std::string::npos)
      << agreement.findings[0].measured;
}

TEST(ComputeAgreement, NoWrongRelocalizationNeedsGroundTruth) {
  const std::vector<std::string> findings = {"No wrong re-localization was accepted."};
  AgreementReport agreement = ComputeAgreement({Relocalization()}, Matrix(true), Paper(findings));
  EXPECT_EQ(agreement.findings[0].verdict, FindingVerdict::kNotDecided);
  ReportTable wrong(kTableWrongCount, "wrong", kRows, kFeatures);
  wrong.SetMeasured("2", "SI", 3);
  wrong.SetMeasured("1|2|3", "SI", 3);  // the same jobs again: not counted twice
  agreement = ComputeAgreement({Relocalization(), wrong}, Matrix(true), Paper(findings));
  EXPECT_EQ(agreement.findings[0].verdict, FindingVerdict::kNotReproduced);
  EXPECT_EQ(agreement.findings[0].measured.rfind("3 wrong", 0), 0u)
      << agreement.findings[0].measured;
}

TEST(ComputeAgreement, FeaturesWithinTheResolutionMayTradePlaces) {
  // BK's single maps raised to a mean of 64.5, 0.5 below SU's 65.
  ReportTable table = Relocalization();
  table.SetMeasured("1", "BK", 59.5);
  table.SetMeasured("2", "BK", 67.0);
  table.SetMeasured("3", "BK", 67.0);
  const AgreementReport agreement = ComputeAgreement({table}, Matrix(true), Paper({}));
  const RankAgreement& ranking = agreement.ranking;
  // Measured SI > SU > BK as before (rho 0.5); SI > BK > SU against the
  // paper's SU > SI > BK gives 1 - 6*6/24 = -0.5.
  EXPECT_NEAR(*ranking.spearman_rho, 0.5, 1e-12);
  EXPECT_NEAR(*ranking.spearman_rho_low, -0.5, 1e-12);
  EXPECT_NEAR(*ranking.spearman_rho_high, 0.5, 1e-12);
  ASSERT_EQ(ranking.close_pairs.size(), 1u);
  EXPECT_EQ(ranking.close_pairs[0].higher, "SU");
  EXPECT_EQ(ranking.close_pairs[0].lower, "BK");
  EXPECT_NEAR(ranking.close_pairs[0].gap_pts, 0.5, 1e-12);
  const std::string markdown = AgreementToMarkdown(agreement);
  EXPECT_NE(markdown.find("; within 1.0 points of each other, an order one run does not decide: "
                          "SU/BK 0.5; ρ over the orders they allow -0.50 to 0.50"),
            std::string::npos)
      << markdown;
  const nlohmann::json json = AgreementToJson(agreement);
  EXPECT_DOUBLE_EQ(json.at("ranking").at("spearman_rho_low").get<double>(), -0.5);
  EXPECT_DOUBLE_EQ(json.at("ranking").at("rank_resolution_pts").get<double>(), kRankResolutionPts);
  EXPECT_EQ(json.at("ranking").at("close_pairs").at(0).at("lower"), "BK");
}

TEST(ComputeAgreement, ConsecutiveSharesBesideThePathsBound) {
  const std::vector<std::string> rows = {"30 min", "60 min"};
  ReportTable within(kTableConsecutiveWithin55cmPct, "within", rows, kFeatures);
  ReportTable bound(kTableConsecutiveWithin55cmBoundPct, "bound", rows, kFeatures);
  within.SetMeasured("30 min", "SU", 71.0);
  within.SetPaper("30 min", "SU", 93.0);
  bound.SetMeasured("30 min", "SU", 80.6);
  within.SetMeasured("30 min", "OR", 40.0);  // no paper value: listed without one
  bound.SetMeasured("30 min", "OR", 80.6);
  within.SetMeasured("30 min", "SI", 67.0);  // bound not recorded: left out
  within.SetMeasured("60 min", "SU", 55.0);
  const AgreementReport agreement =
      ComputeAgreement({Relocalization(), within, bound}, Matrix(true), Paper({}));
  ASSERT_EQ(agreement.consecutive_bounds.size(), 1u);  // 60 min has no bound at all
  const ConsecutiveBound& b = agreement.consecutive_bounds[0];
  EXPECT_EQ(b.row, "30 min");
  EXPECT_EQ(b.features, (std::vector<std::string>{"SU", "OR"}));
  EXPECT_EQ(b.measured_pct, (std::vector<double>{71.0, 40.0}));
  EXPECT_EQ(b.bound_pct, (std::vector<double>{80.6, 80.6}));
  EXPECT_EQ(b.paper_pct[0], 93.0);
  EXPECT_FALSE(b.paper_pct[1].has_value());
  const std::string markdown = AgreementToMarkdown(agreement);
  EXPECT_NE(markdown.find("30 min: SU 71/81 (93) OR 40/81;"), std::string::npos) << markdown;
  const nlohmann::json json = AgreementToJson(agreement);
  EXPECT_EQ(json.at("consecutive_bounds").at(0).at("paper_pct").at(1), nullptr);
  // Without the bound table (reports written before it) there is no line.
  const AgreementReport without = ComputeAgreement({Relocalization(), within}, Matrix(true), Paper({}));
  EXPECT_TRUE(without.consecutive_bounds.empty());
  EXPECT_EQ(AgreementToMarkdown(without).find("against the paths' bound"), std::string::npos);
}

TEST(AgreementOutput, MarkdownAndJsonCarryTheNumbers) {
  const AgreementReport agreement =
      ComputeAgreement({Relocalization()}, Matrix(true),
                       Paper({"Single-session maps: re-localization is best on the diagonal"}));
  const std::string markdown = AgreementToMarkdown(agreement);
  EXPECT_NE(markdown.find("| re-localization, single-session maps | points | 9 | 5.7 |"),
            std::string::npos)
      << markdown;
  EXPECT_NE(markdown.find("Spearman ρ = 0.50 over 3 features"), std::string::npos);
  EXPECT_EQ(markdown.find("an order one run does not decide"), std::string::npos);
  EXPECT_NE(markdown.find("+6.0 points (paper +6.0)"), std::string::npos);
  // A cell naming the closest-in-time row keeps the table's columns.
  AgreementReport piped = agreement;
  piped.deviations[0].worst_cell = "SU on 1|2|3: 50 (paper 60)";
  EXPECT_NE(AgreementToMarkdown(piped).find("(SU on 1\\|2\\|3: 50 (paper 60))"), std::string::npos);
  const nlohmann::json json = AgreementToJson(agreement);
  EXPECT_EQ(json.at("deviations").at(0).at("cells"), 9);
  EXPECT_EQ(json.at("deviations").at(2).at("mean_abs_deviation"), nullptr);
  EXPECT_DOUBLE_EQ(json.at("ranking").at("spearman_rho").get<double>(), 0.5);
  EXPECT_EQ(json.at("findings").at(0).at("verdict"), "reproduced");
  EXPECT_EQ(json.at("findings_reproduced"), 1);
}

}  // namespace
}  // namespace duskmap
