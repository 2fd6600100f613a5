#include "slam/synthetic/assets/mtl_file.h"

#include <set>

#include "slam/core/check.h"
#include "slam/synthetic/assets/obj_text.h"

namespace duskmap {
namespace {

// Reads the statements of one material while naming the file and line.
class MtlStatement {
 public:
  MtlStatement(std::string_view rest, const std::string& source, int line)
      : rest_(rest), source_(source), line_(line) {}

  // One to `max_count` numbers, each in [min, max]; what follows is an error.
  std::vector<float> Numbers(const char* keyword, size_t max_count, double min, double max) {
    std::vector<float> values;
    for (std::string_view token = NextObjToken(&rest_); !token.empty(); token = NextObjToken(&rest_)) {
      const std::optional<double> value = ParseObjNumber(token);
      SLAM_THROW_IF_NOT(InputError, value.has_value())
          << source_ << ":" << line_ << ": " << keyword << ": malformed number '" << token << "'";
      SLAM_THROW_IF_NOT(InputError, *value >= min && *value <= max)
          << source_ << ":" << line_ << ": " << keyword << ": " << token << " is outside [" << min << ", " << max
          << "]";
      values.push_back(static_cast<float>(*value));
    }
    SLAM_THROW_IF_NOT(InputError, !values.empty() && values.size() <= max_count)
        << source_ << ":" << line_ << ": " << keyword << " needs 1 to " << max_count << " numbers, got "
        << values.size();
    return values;
  }

  Eigen::Vector3f Colour(const char* keyword) {
    std::string_view peek = rest_;
    const std::string_view first = NextObjToken(&peek);
    SLAM_THROW_IF_NOT(InputError, first != "spectral" && first != "xyz")
        << source_ << ":" << line_ << ": " << keyword << " " << first << " is not supported (only r g b)";
    const std::vector<float> v = Numbers(keyword, 3, 0.0, 1e6);
    SLAM_THROW_IF_NOT(InputError, v.size() != 2)
        << source_ << ":" << line_ << ": " << keyword << " needs 1 or 3 numbers, got 2";
    return v.size() == 1 ? Eigen::Vector3f::Constant(v[0]) : Eigen::Vector3f(v[0], v[1], v[2]);
  }

  float Dissolve(const char* keyword) {
    std::string_view peek = rest_;
    SLAM_THROW_IF_NOT(InputError, NextObjToken(&peek) != "-halo")
        << source_ << ":" << line_ << ": " << keyword << " -halo is not supported";
    return Numbers(keyword, 1, 0.0, 1.0)[0];
  }

  // map_Kd [-s u [v [w]]] [-o u [v [w]]] file name
  MtlTextureReference TextureMap(const char* keyword) {
    MtlTextureReference map;
    map.line = line_;
    while (true) {
      std::string_view peek = rest_;
      const std::string_view token = NextObjToken(&peek);
      if (token.empty() || token.front() != '-') break;
      SLAM_THROW_IF_NOT(InputError, token == "-s" || token == "-o")
          << source_ << ":" << line_ << ": " << keyword << " option " << token
          << " is not supported (only -s and -o)";
      rest_ = peek;
      const Eigen::Vector3f values = OptionValues(keyword, token);
      (token == "-s" ? map.scale : map.offset) = values.head<2>();
    }
    map.file_name = std::string(TrimObjBlanks(rest_));
    SLAM_THROW_IF_NOT(InputError, !map.file_name.empty())
        << source_ << ":" << line_ << ": " << keyword << " has no file name";
    return map;
  }

 private:
  // The 1 to 3 numbers after a texture option (u [v [w]]; v and w default
  // to u's default, as the MTL specification says: 1 for -s, 0 for -o).
  Eigen::Vector3f OptionValues(const char* keyword, std::string_view option) {
    Eigen::Vector3f values = Eigen::Vector3f::Constant(option == "-s" ? 1.0f : 0.0f);
    int count = 0;
    while (count < 3) {
      std::string_view peek = rest_;
      const std::optional<double> value = ParseObjNumber(NextObjToken(&peek));
      if (!value.has_value()) break;
      values[count++] = static_cast<float>(*value);
      rest_ = peek;
    }
    SLAM_THROW_IF_NOT(InputError, count > 0)
        << source_ << ":" << line_ << ": " << keyword << " " << option << " needs a number";
    return values;
  }

  std::string_view rest_;
  const std::string& source_;
  int line_;
};

}  // namespace

std::vector<MtlMaterial> ParseMtl(const std::string& text, const std::string& source) {
  std::vector<MtlMaterial> materials;
  std::set<std::string> names;
  bool skipping = false;  // inside a repeated definition
  bool has_d = false;     // the current material gave d (which wins over Tr)
  ObjTextLines lines(text);
  std::string_view line;
  int number = 0;
  while (lines.Next(&line, &number)) {
    std::string_view rest = line;
    const std::string_view keyword = NextObjToken(&rest);
    if (keyword == "newmtl") {
      const std::string name(TrimObjBlanks(rest));
      SLAM_THROW_IF_NOT(InputError, !name.empty()) << source << ":" << number << ": newmtl without a name";
      skipping = !names.insert(name).second;
      if (!skipping) materials.push_back({name, Eigen::Vector3f::Constant(0.8f), std::nullopt, std::nullopt, number});
      has_d = false;
      continue;
    }
    const bool used = keyword == "Kd" || keyword == "d" || keyword == "Tr" || keyword == "map_Kd";
    if (!used) continue;
    SLAM_THROW_IF_NOT(InputError, !materials.empty())
        << source << ":" << number << ": " << keyword << " before the first newmtl";
    if (skipping) continue;
    MtlMaterial& material = materials.back();
    MtlStatement statement(rest, source, number);
    if (keyword == "Kd") {
      material.diffuse_rgb = statement.Colour("Kd");
    } else if (keyword == "d") {
      material.dissolve = statement.Dissolve("d");
      has_d = true;
    } else if (keyword == "Tr") {
      const float transparency = statement.Dissolve("Tr");
      if (!has_d) material.dissolve = 1.0f - transparency;
    } else {
      material.diffuse_map = statement.TextureMap("map_Kd");
    }
  }
  return materials;
}

}  // namespace duskmap
