// The files a feature column reads besides the dataset's images (an ONNX
// model, an h5 feature file or a folder of them, SuperGlue's model), each
// with the checksum of its bytes (core/file_checksum.h): part of the run's
// configuration record (a resume after a model or h5 file changed is
// refused) and of the feature cache's key (a changed file is never reused),
// whatever the file's size and time say.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "slam/engine/engine_options.h"
#include "slam/experiment/experiment_config.h"
#include "slam/features/feature_options.h"

namespace duskmap {

// The paths the feature type reads (FeatureFilePath): onnx and superpoint
// their model, h5 its file, or every regular file of its folder (sorted),
// dusknet the model its model_path names; none for the others.
std::vector<std::string> FeatureFilesOf(const FeatureOptions& features);

// {"embedded:dusknet.onnx": 16 hexadecimal digits} for a type that runs the
// model embedded in the program (dusknet without model_path), keyed and
// recorded beside the files' checksums; {} for the others.
nlohmann::json EmbeddedModelChecksums(const FeatureOptions& features);

// {path: 16 hexadecimal digits} of `paths`; a path that does not exist is
// recorded as null (the column is skipped or its extractor names it). Throws
// InputError naming a file that exists but cannot be read.
nlohmann::json FileChecksums(const std::vector<std::string>& paths);

// The checksums of the files read by the columns `labels` of the run (their
// extractors, and SuperGlue's model for a column matched by it), one record.
nlohmann::json RunFeatureFileChecksums(const ExperimentOptions& experiment,
                                       const EngineOptions& engine,
                                       const std::vector<std::string>& labels);

}  // namespace duskmap
