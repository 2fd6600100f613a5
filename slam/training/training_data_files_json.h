// JSON codecs of a training-data folder's manifest.json (training_data_files.h;
// slam/core/json_codec.h). "format" and "version" are the file's: the writer
// adds them and the reader checks them before the rest.
#pragma once

#include "slam/core/json_codec.h"
#include "slam/training/training_data_files.h"
#include "slam/training/training_data_options_json.h"

namespace duskmap {

template <>
struct JsonCodec<TrainingSceneRecord> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("index", o.index, JsonRequired{});
    f("seed", o.seed, JsonRequired{});
    f("texture_seed", o.texture_seed, JsonRequired{});
    f("day_of_year", o.day_of_year, JsonRequired{});
    f("clock_times", o.clock_times, JsonRequired{});
    f("furniture_signature_hash", o.furniture_signature_hash, JsonRequired{});
    f("split", o.split, JsonRequired{});
    f("first_pair", o.first_pair, JsonRequired{});
    f("pairs", o.pairs, JsonRequired{});
  }
};

template <>
struct JsonCodec<TrainingDataFile> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("name", o.name, JsonRequired{});
    f("dtype", o.dtype, JsonRequired{});
    f("shape", o.shape, JsonRequired{});
    f("bytes", o.bytes, JsonRequired{});
  }
};

template <>
struct JsonCodec<TrainingDataManifest> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("data", o.data, JsonRequired{});
    f("patch", o.patch, JsonRequired{});
    f("scenes", o.scenes, JsonRequired{});
    f("pairs", o.pairs, JsonRequired{});
    f("train_pairs", o.train_pairs, JsonRequired{});
    f("validation_pairs", o.validation_pairs, JsonRequired{});
    f("files", o.files, JsonRequired{});
  }
};

}  // namespace duskmap
