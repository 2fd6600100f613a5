// The one reader of JSON text: every JSON file duskmap reads (configs,
// manifests, run.json, job summaries, cached summaries, a map's stored
// options) is parsed here, so that every such file gets the same checks and
// the same one-line errors:
//  - invalid JSON, with the line and column where parsing stopped;
//  - a key given twice in one object (nlohmann would keep the last silently);
//  - a number outside double's range ("1e400", which nlohmann reports as an
//    internal "number overflow"), named by its key path;
//  - nesting deeper than kMaxJsonDepth arrays and objects, refused while
//    parsing, before a deep tree is built: nlohmann's copy and dump() recurse
//    once per level, and '[' * 200000 overflowed the stack in every reader.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace duskmap {

// No file duskmap reads or writes nests more than a handful of levels; a run's
// run.json embeds the experiment config two levels down.
inline constexpr int kMaxJsonDepth = 64;

// Parses JSON text; throws ConfigError("<where>...: <problem>") as above.
nlohmann::json ParseJsonText(const std::string& text, const std::string& where);

// Parses a JSON file; throws ConfigError("<path>: <problem>") when it cannot:
// unreadable, or any of ParseJsonText's problems.
nlohmann::json ReadJsonFile(const std::string& path);

}  // namespace duskmap
