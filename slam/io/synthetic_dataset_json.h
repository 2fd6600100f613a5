// JSON codecs of a synthetic dataset's manifest.json (synthetic_dataset.h;
// slam/core/json_codec.h):
//   {"format": "duskmap-synthetic", "version": 1,
//    "sessions": [{"name": "1", "folder": "1", "clock_time": "16:46", "role": "mapping",
//                   "largest_step_m": 0.49}, ...],
//    "assets": [{"name": "Bed", "source": "...", "creator": "...", "license": "..."}, ...]}
// "format" and "version" are the file's, not the manifest's: WriteManifest
// and ReadManifest add and check them. "assets" is left out when there are
// none, as datasets were written before furniture models existed, and
// "largest_step_m" when not recorded (datasets written before 2026-12-07).
#pragma once

#include "slam/core/json_codec.h"
#include "slam/io/synthetic_dataset.h"

namespace duskmap {

template <>
struct JsonCodec<ManifestSession> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("name", o.name, JsonRequired{});
    f("folder", o.folder, JsonRequired{});
    f("clock_time", o.clock_time);
    f("role", o.role);
    f("largest_step_m", o.largest_step_m, JsonOmitEmpty{});
  }
};

template <>
struct JsonCodec<ManifestAsset> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("name", o.name, JsonRequired{});
    f("source", o.source, JsonRequired{});
    f("creator", o.creator);
    f("license", o.license, JsonRequired{});
  }
};

template <>
struct JsonCodec<DatasetManifest> {
  template <typename F, typename O>
  static void Visit(F& f, O& o) {
    f("sessions", o.sessions, JsonRequired{});
    f("assets", o.assets, JsonOmitEmpty{});
  }
};

}  // namespace duskmap
