// What marks a folder as a duskmap synthetic dataset (io/synthetic_dataset.h):
// its manifest's file name and format. Their own header so that output
// safety (io/output_safety.h, which recognises a dataset that --overwrite may
// replace) does not depend on the dataset reader, which reads through it.
#pragma once

namespace duskmap {

inline constexpr const char* kManifestFileName = "manifest.json";
inline constexpr const char* kSyntheticFormat = "duskmap-synthetic";

}  // namespace duskmap
