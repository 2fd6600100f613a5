// Writing the engine's per-frame records: JSON lines or CSV (one row per
// frame, the same fields), and the corrected trajectory in TUM format.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "slam/engine/localization_record.h"
#include "slam/engine/mapper.h"

namespace duskmap {

nlohmann::json LocalizationRecordToJson(const LocalizationRecord& record);
nlohmann::json MappingResultToJson(const MappingFrameResult& result);

// One JSON object per line.
void WriteJsonLines(std::ostream& out, const std::vector<nlohmann::json>& rows);
// A header from the first row's keys (nested objects flattened with '.'),
// then one line per row; absent values are empty cells.
void WriteCsv(std::ostream& out, const std::vector<nlohmann::json>& rows);

// The corrected camera poses (frames with one) as a TUM trajectory file;
// throws InputError when the file cannot be written.
void WriteCorrectedTrajectory(const std::string& path,
                              const std::vector<LocalizationRecord>& records);

}  // namespace duskmap
