#include "slam/core/json_reader.h"

#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "slam/core/check.h"
#include "slam/core/input_file.h"

namespace duskmap {
namespace {

// The parser's position, kept from its callbacks: the open arrays and objects
// with their paths ("matrix.features[2]"), the keys seen in each open object
// and the index of the element being read in each open array.
class JsonPosition {
 public:
  explicit JsonPosition(const std::string& where) : where_(where) {}

  bool OnEvent(nlohmann::json::parse_event_t event, const nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        // Thrown here, before the level is built: nothing deeper is ever
        // held, so unwinding stays shallow too.
        SLAM_THROW_IF_NOT(ConfigError, static_cast<int>(open_.size()) < kMaxJsonDepth)
            << where_ << ": arrays and objects nested deeper than " << kMaxJsonDepth
            << " levels";
        open_.push_back({event == Event::array_start, ValuePath(), DuplicatePath(), {}, 0});
        break;
      case Event::object_end:
      case Event::array_end:
        open_.pop_back();
        EndValue();
        break;
      case Event::key:
        last_key_ = parsed.get<std::string>();
        if (!open_.back().keys.insert(last_key_).second && duplicate_.empty()) {
          duplicate_ = DuplicatePath();
        }
        break;
      case Event::value:
        EndValue();
        break;
    }
    return true;
  }

  // The path of the value being read: "a.b[3].c", "" at the top.
  std::string ValuePath() const {
    if (open_.empty()) return "";
    const Open& in = open_.back();
    if (in.array) return in.path + "[" + std::to_string(in.index) + "]";
    return in.path.empty() ? last_key_ : in.path + "." + last_key_;
  }

  // The first key given twice, as "sessions[].name"; "" when none.
  const std::string& duplicate() const { return duplicate_; }

 private:
  struct Open {
    bool array = false;
    std::string path;            // ValuePath() of this array or object
    std::string duplicate_path;  // the same with "[]" for every array index
    std::set<std::string> keys;  // objects: the keys seen so far
    size_t index = 0;            // arrays: the element being read
  };

  // The path of the value being read, array indices left out.
  std::string DuplicatePath() const {
    if (open_.empty()) return "";
    const Open& in = open_.back();
    if (in.array) return in.duplicate_path + "[]";
    return in.duplicate_path.empty() ? last_key_ : in.duplicate_path + "." + last_key_;
  }

  void EndValue() {
    if (!open_.empty() && open_.back().array) ++open_.back().index;
  }

  const std::string& where_;
  std::vector<Open> open_;
  std::string last_key_;
  std::string duplicate_;
};

// 1-based line and column of the 1-based byte offset `byte` of `text`.
std::string LineAndColumn(const std::string& text, size_t byte) {
  size_t line = 1, column = 1;
  for (size_t i = 0; i + 1 < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return std::to_string(line) + ":" + std::to_string(column);
}

// nlohmann's message without its "[json.exception.parse_error.101] ... : " prefix.
std::string Reason(const std::string& what) {
  const size_t colon = what.find(": ");
  return colon == std::string::npos ? what : what.substr(colon + 2);
}

}  // namespace

nlohmann::json ParseJsonText(const std::string& text, const std::string& where) {
  JsonPosition position(where);
  const nlohmann::json::parser_callback_t track =
      [&](int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
        return position.OnEvent(event, parsed);
      };
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(text, track);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is the 1-based offset where parsing stopped.
    SLAM_THROW(ConfigError) << where << ":" << LineAndColumn(text, e.byte) << ": invalid JSON ("
                            << Reason(e.what()) << ")";
  } catch (const nlohmann::json::out_of_range& e) {
    // A number beyond double's range: "number overflow parsing '1e400'".
    std::string number = Reason(e.what());
    const size_t quote = number.find('\'');
    if (quote != std::string::npos && number.size() > quote + 1 && number.back() == '\'') {
      number = number.substr(quote + 1, number.size() - quote - 2);
    }
    const std::string path = position.ValuePath();
    SLAM_THROW(ConfigError) << where << ": " << (path.empty() ? "" : path + ": ")
                            << "number out of range (" << number << ")";
  }
  SLAM_THROW_IF_NOT(ConfigError, position.duplicate().empty())
      << where << ": key '" << position.duplicate() << "' is given twice";
  return json;
}

nlohmann::json ReadJsonFile(const std::string& path) {
  RefuseNonRegularFile(path);  // before opening: a FIFO would block
  std::ifstream in(path);
  SLAM_THROW_IF_NOT(ConfigError, in.good()) << path << ": cannot open file";
  std::stringstream buffer;
  buffer << in.rdbuf();
  return ParseJsonText(buffer.str(), path);
}

}  // namespace duskmap
