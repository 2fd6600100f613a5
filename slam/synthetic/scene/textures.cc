#include "slam/synthetic/scene/textures.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"
#include "slam/core/random.h"
#include "slam/io/image_header.h"
#include "slam/io/path_status.h"
#include "slam/synthetic/scene/photo_materials.h"
#include "slam/synthetic/scene/relief.h"
#include "slam/synthetic/scene/value_noise.h"

namespace duskmap {
namespace {

cv::Vec3f RandomColor(cv::RNG& rng, float lo, float hi) {
  return cv::Vec3f(rng.uniform(lo, hi), rng.uniform(lo, hi), rng.uniform(lo, hi));
}

cv::Scalar ToScalar(const cv::Vec3f& c) { return cv::Scalar(c[0], c[1], c[2]); }

// Modulates a constant colour by (1 + amount * noise).
cv::Mat Modulated(cv::Size size, const cv::Vec3f& color, const cv::Mat& noise, float amount) {
  cv::Mat out(size, CV_32FC3);
  for (int r = 0; r < size.height; ++r) {
    const float* n = noise.ptr<float>(r);
    cv::Vec3f* o = out.ptr<cv::Vec3f>(r);
    for (int c = 0; c < size.width; ++c) o[c] = color * (1.0f + amount * n[c]);
  }
  return out;
}

void DrawRandomShapes(cv::Mat& image, int count, cv::RNG& rng, float lo, float hi) {
  const int w = image.cols, h = image.rows;
  for (int i = 0; i < count; ++i) {
    const cv::Scalar color = ToScalar(RandomColor(rng, lo, hi));
    const cv::Point p(rng.uniform(0, w), rng.uniform(0, h));
    const int extent = std::max(2, rng.uniform(std::max(1, w / 30), std::max(2, w / 5)));
    switch (rng.uniform(0, 4)) {
      case 0: cv::circle(image, p, extent / 2, color, cv::FILLED, cv::LINE_AA); break;
      case 1:
        cv::rectangle(image, p, p + cv::Point(extent, rng.uniform(2, extent + 3)), color, cv::FILLED);
        break;
      case 2:
        cv::line(image, p, cv::Point(rng.uniform(0, w), rng.uniform(0, h)), color,
                 std::max(1, extent / 12), cv::LINE_AA);
        break;
      default: {
        std::vector<cv::Point> tri = {p, p + cv::Point(extent, rng.uniform(-extent, extent)),
                                      p + cv::Point(rng.uniform(-extent, extent), extent)};
        cv::fillConvexPoly(image, tri, color, cv::LINE_AA);
      }
    }
  }
}

void DrawText(cv::Mat& image, int lines, cv::RNG& rng, float lo, float hi) {
  static const char* kWords[] = {"SUNSET", "MAISON", "Quebec", "1984", "JAZZ", "Expo",
                                 "NORD",   "cafe",   "DUSK",   "Art",  "Lumiere", "42"};
  for (int i = 0; i < lines; ++i) {
    const std::string text = std::string(kWords[rng.uniform(0, 12)]) + " " + kWords[rng.uniform(0, 12)];
    const double scale = image.cols / 260.0 * rng.uniform(0.6, 1.4);
    const cv::Point origin(rng.uniform(0, std::max(1, image.cols / 3)), rng.uniform(image.rows / 8, image.rows));
    cv::putText(image, text, origin, rng.uniform(0, 2) ? cv::FONT_HERSHEY_DUPLEX : cv::FONT_HERSHEY_SIMPLEX,
                scale, ToScalar(RandomColor(rng, lo, hi)), std::max(1, static_cast<int>(scale * 2)),
                cv::LINE_AA);
  }
}

cv::Mat GradientBackground(cv::Size size, cv::RNG& rng) {
  const cv::Vec3f a = RandomColor(rng, 0.05f, 0.8f), b = RandomColor(rng, 0.05f, 0.8f);
  cv::Mat out(size, CV_32FC3);
  for (int r = 0; r < size.height; ++r) {
    const float s = static_cast<float>(r) / std::max(1, size.height - 1);
    out.row(r).setTo(ToScalar(a * (1.0f - s) + b * s));
  }
  return out;
}

void AddFrame(cv::Mat& image, const cv::Vec3f& color) {
  const int border = std::max(2, std::min(image.cols, image.rows) / 14);
  cv::rectangle(image, cv::Rect(0, 0, image.cols, image.rows), ToScalar(color), 2 * border);
}

cv::Mat UserPicture(cv::Size size, const std::vector<cv::Mat>& user_images, cv::RNG& rng) {
  const cv::Mat& source = user_images[rng.uniform(0, static_cast<int>(user_images.size()))];
  cv::Mat resized, as_float;
  cv::resize(source, resized, size, 0, 0, cv::INTER_AREA);
  resized.convertTo(as_float, CV_32FC3, 1.0 / 255.0);
  cv::pow(as_float, 2.2, as_float);  // sRGB-ish to linear albedo
  return as_float * 0.9;
}

cv::Mat MakeBooks(cv::Size size, cv::RNG& rng, ReliefCanvas& relief) {
  cv::Mat out(size, CV_32FC3, cv::Scalar(0.12, 0.16, 0.22));  // shelf wood
  const int shelf_rows = std::max(1, static_cast<int>(std::lround(size.height / 70.0)));
  const int shelf_h = size.height / shelf_rows;
  for (int s = 0; s < shelf_rows; ++s) {
    const int top = s * shelf_h + shelf_h / 10, bottom = (s + 1) * shelf_h - shelf_h / 12;
    int x = rng.uniform(0, 6);
    while (x < size.width) {
      const int w = rng.uniform(4, 14);
      const int h = static_cast<int>((bottom - top) * rng.uniform(0.6, 1.0));
      const cv::Vec3f color = RandomColor(rng, 0.03f, 0.7f);
      cv::rectangle(out, cv::Rect(x, bottom - h, w, h), ToScalar(color), cv::FILLED);
      if (relief.enabled()) {  // a rounded spine, 10 mm proud at its middle
        for (int k = 0; k < w; ++k) {
          const double across = (k + 0.5) / w * 2.0 - 1.0;
          relief.AddRect(cv::Rect(x + k, bottom - h, 1, h), 0.010 * std::sqrt(1.0 - across * across));
        }
      }
      cv::line(out, cv::Point(x + 1, bottom - h * 3 / 4), cv::Point(x + w - 2, bottom - h * 3 / 4),
               ToScalar(color * 0.3f), 1);
      if (rng.uniform(0, 3) == 0) {
        cv::rectangle(out, cv::Rect(x + 1, bottom - h / 2, std::max(1, w - 2), h / 8),
                      ToScalar(RandomColor(rng, 0.5f, 0.9f)), cv::FILLED);
      }
      x += w + (rng.uniform(0, 8) == 0 ? rng.uniform(5, 25) : 0);
    }
  }
  return out;
}

cv::Mat MakeWindow(cv::Size size, cv::RNG& rng) {
  // Radiance pattern relative to the sky: bright sky above, darker silhouettes
  // of buildings and trees below, dark mullions.
  cv::Mat out(size, CV_32FC3);
  for (int r = 0; r < size.height; ++r) {
    const float s = static_cast<float>(r) / size.height;
    out.row(r).setTo(cv::Scalar(1.1 - 0.3 * s, 1.0 - 0.2 * s, 0.9 - 0.1 * s));
  }
  const int horizon = size.height * 2 / 3;
  for (int x = 0; x < size.width;) {
    const int w = rng.uniform(size.width / 8, size.width / 3);
    const int top = horizon - rng.uniform(0, size.height / 4);
    cv::rectangle(out, cv::Rect(x, top, w, size.height - top), cv::Scalar(0.18, 0.2, 0.22), cv::FILLED);
    x += w;
  }
  for (int i = 0; i < 5; ++i) {
    cv::circle(out, cv::Point(rng.uniform(0, size.width), horizon - rng.uniform(0, size.height / 5)),
               rng.uniform(size.width / 12, size.width / 5), cv::Scalar(0.08, 0.14, 0.1), cv::FILLED,
               cv::LINE_AA);
  }
  const int bar = std::max(2, size.width / 25);
  cv::rectangle(out, cv::Rect(0, 0, size.width, size.height), cv::Scalar(0.03, 0.03, 0.03), 2 * bar);
  cv::rectangle(out, cv::Rect(size.width / 2 - bar / 2, 0, bar, size.height), cv::Scalar(0.03, 0.03, 0.03), cv::FILLED);
  cv::rectangle(out, cv::Rect(0, size.height / 2 - bar / 2, size.width, bar), cv::Scalar(0.03, 0.03, 0.03), cv::FILLED);
  return out;
}

cv::Mat MakeCabinet(cv::Size size, const cv::Vec3f& base, cv::RNG& rng, ReliefCanvas& relief) {
  cv::Mat out = Modulated(size, base, ValueNoise(size, 6.0, rng), 0.05f);
  // Doors about 0.4-0.6 m wide (texels of 4 mm): split the width evenly.
  const int doors = std::max(1, static_cast<int>(std::lround(size.width / 125.0)));
  const int door_w = size.width / doors;
  const int drawers = size.height > 150 && rng.uniform(0, 2) ? 1 : 0;
  const int drawer_h = drawers ? std::min(size.height / 4, 60) : 0;
  const cv::Scalar edge = ToScalar(base * 0.45f), bevel = ToScalar(base * 1.25f);
  const cv::Scalar metal = ToScalar(RandomColor(rng, 0.15f, 0.6f));
  for (int d = 0; d < doors; ++d) {
    const int x0 = d * door_w;
    cv::rectangle(out, cv::Rect(x0, 0, door_w, size.height), edge, 2);
    relief.GrooveColumn(x0, 0.006);  // the gap between doors
    if (drawers) {
      cv::line(out, {x0, drawer_h}, {x0 + door_w, drawer_h}, edge, 2);
      cv::rectangle(out, cv::Rect(x0 + door_w / 2 - 12, drawer_h / 2 - 2, 24, 5), metal, cv::FILLED);
      relief.GrooveRow(drawer_h, 0.006);
      relief.AddRect(cv::Rect(x0 + door_w / 2 - 12, drawer_h / 2 - 2, 24, 5), 0.02);
    }
    const int m = std::max(4, door_w / 8);
    cv::rectangle(out, cv::Rect(x0 + m, drawer_h + m, door_w - 2 * m, size.height - drawer_h - 2 * m), bevel, 1);
    cv::rectangle(out, cv::Rect(x0 + m + 2, drawer_h + m + 2, door_w - 2 * m - 4, size.height - drawer_h - 2 * m - 4), edge, 1);
    // The panel sits 10 mm back, with a 2-texel bevel down to it.
    relief.AddRect(cv::Rect(x0 + m, drawer_h + m, door_w - 2 * m, size.height - drawer_h - 2 * m), -0.005);
    relief.AddRect(cv::Rect(x0 + m + 2, drawer_h + m + 2, door_w - 2 * m - 4, size.height - drawer_h - 2 * m - 4), -0.005);
    const int hx = d % 2 ? x0 + m / 2 + 1 : x0 + door_w - m / 2 - 3;
    const int hy = drawer_h + (size.height - drawer_h) / 3;
    cv::rectangle(out, cv::Rect(hx, hy, 3, std::min(30, std::max(6, size.height / 8))), metal, cv::FILLED);
    relief.AddRect(cv::Rect(hx, hy, 3, std::min(30, std::max(6, size.height / 8))), 0.02);
  }
  return out;
}

cv::Mat MakeRadiator(cv::Size size, const cv::Vec3f& base, cv::RNG& rng, ReliefCanvas& relief) {
  cv::Mat out = Modulated(size, base, ValueNoise(size, 8.0, rng), 0.03f);
  const int fin = 12;
  // Fins: a 25 mm deep corrugation whose troughs are the dark lines below.
  for (int x = 0; x < size.width && relief.enabled(); ++x) {
    const double phase = std::sin(3.14159265358979 * (x - fin / 2) / fin);
    relief.AddRect(cv::Rect(x, 0, 1, size.height), 0.025 * phase * phase);
  }
  for (int x = fin / 2; x < size.width; x += fin) {
    cv::line(out, {x, 3}, {x, size.height - 4}, ToScalar(base * 0.55f), 2);
    cv::line(out, {x + 3, 3}, {x + 3, size.height - 4}, ToScalar(base * 1.15f), 1);
  }
  cv::rectangle(out, cv::Rect(0, 0, size.width, size.height), ToScalar(base * 0.6f), 2);
  cv::circle(out, {size.width - 8, size.height - 8}, 4, cv::Scalar(0.35, 0.4, 0.45), cv::FILLED);  // valve
  return out;
}

cv::Mat MakeCurtain(cv::Size size, const cv::Vec3f& base, cv::RNG& rng, ReliefCanvas& relief) {
  cv::Mat out = Modulated(size, base, ValueNoise(size, 1.5, rng), 0.08f);
  const cv::Vec3f accent = RandomColor(rng, 0.05f, 0.7f);
  if (rng.uniform(0, 2)) {  // stripes
    const int period = rng.uniform(18, 40);
    for (int x = rng.uniform(0, period); x < size.width; x += period) {
      cv::rectangle(out, cv::Rect(x, 0, std::max(2, period / 4), size.height), ToScalar(accent), cv::FILLED);
    }
  } else {  // scattered motif
    const int motifs = size.area() / 900;
    for (int i = 0; i < motifs; ++i) {
      const cv::Point p(rng.uniform(0, size.width), rng.uniform(0, size.height));
      const int r = rng.uniform(3, 9);
      cv::circle(out, p, r, ToScalar(accent), cv::FILLED, cv::LINE_AA);
      cv::circle(out, p + cv::Point(r, -r), r / 2 + 1, ToScalar(accent * 0.6f), cv::FILLED, cv::LINE_AA);
    }
  }
  // Folds: a slow shading across the width (the hollows see less of the
  // room) and, as relief, 50 mm waves of the same period.
  for (int c = 0; c < size.width; ++c) {
    const float fold = 0.82f + 0.18f * static_cast<float>(std::sin(c * 2.0 * 3.14159265 / 35.0));
    for (int r = 0; r < size.height; ++r) out.at<cv::Vec3f>(r, c) *= fold;
    relief.AddRect(cv::Rect(c, 0, 1, size.height), 0.05 * std::sin(c * 2.0 * 3.14159265 / 35.0));
  }
  return out;
}

cv::Mat MakeScreen(cv::Size size, cv::RNG& rng) {
  cv::Mat out(size, CV_32FC3, cv::Scalar(0.015, 0.015, 0.018));
  const int bezel = std::max(3, std::min(size.width, size.height) / 30);
  // A faint reflection streak on the glass.
  cv::Mat streak = ValueNoise(size, 40.0, rng);
  for (int r = 0; r < size.height; ++r) {
    for (int c = 0; c < size.width; ++c) {
      const float v = 0.02f + 0.015f * streak.at<float>(r, c);
      out.at<cv::Vec3f>(r, c) = cv::Vec3f(v, v, v * 1.1f);
    }
  }
  cv::rectangle(out, cv::Rect(0, 0, size.width, size.height), cv::Scalar(0.05, 0.05, 0.05), 2 * bezel);
  cv::circle(out, {size.width / 2, size.height - bezel / 2}, std::max(1, bezel / 4), cv::Scalar(0.6, 0.3, 0.2), cv::FILLED);
  return out;
}

cv::Mat MakePackaging(cv::Size size, const cv::Vec3f& base, cv::RNG& rng) {
  cv::Mat out(size, CV_32FC3, ToScalar(base));
  const cv::Vec3f band = RandomColor(rng, 0.05f, 0.85f);
  const int band_y = rng.uniform(0, std::max(1, size.height / 2));
  cv::rectangle(out, cv::Rect(0, band_y, size.width, std::max(3, size.height / rng.uniform(3, 6))), ToScalar(band), cv::FILLED);
  DrawRandomShapes(out, std::max(3, size.area() / 1500), rng, 0.03f, 0.9f);
  DrawText(out, std::max(1, size.height / 40), rng, 0.01f, 0.95f);
  cv::rectangle(out, cv::Rect(0, 0, size.width, size.height), ToScalar(base * 0.5f), 1);
  return out;
}

cv::Mat MakeWallpaper(cv::Size size, const cv::Vec3f& base, cv::RNG& rng) {
  cv::Mat out = Modulated(size, base, ValueNoise(size, 12.0, rng), 0.04f);
  const cv::Vec3f ink = base * rng.uniform(0.55f, 0.75f);
  const cv::Vec3f leaf = RandomColor(rng, 0.1f, 0.5f);
  // A jittered grid of small motifs: no two alike, so they stay matchable.
  const int cell = 28;
  for (int gy = 0; gy * cell < size.height + cell; ++gy) {
    for (int gx = 0; gx * cell < size.width + cell; ++gx) {
      const cv::Point p(gx * cell + (gy % 2) * cell / 2 + rng.uniform(-6, 7), gy * cell + rng.uniform(-6, 7));
      switch (rng.uniform(0, 3)) {
        case 0:
          cv::circle(out, p, rng.uniform(2, 6), ToScalar(ink), cv::FILLED, cv::LINE_AA);
          break;
        case 1: {
          const double a = rng.uniform(0.0, 3.14159);
          const cv::Point d(static_cast<int>(7 * std::cos(a)), static_cast<int>(7 * std::sin(a)));
          cv::line(out, p - d, p + d, ToScalar(leaf), 2, cv::LINE_AA);
          cv::circle(out, p + d, 3, ToScalar(leaf), cv::FILLED, cv::LINE_AA);
          break;
        }
        default:
          cv::rectangle(out, cv::Rect(p.x - 3, p.y - 3, 6, 6), ToScalar(ink * 0.9f), 1);
      }
    }
  }
  return out;
}

cv::Mat MakeSwitch(cv::Size size, cv::RNG& rng) {
  cv::Mat out(size, CV_32FC3, cv::Scalar(0.78, 0.8, 0.8));
  cv::rectangle(out, cv::Rect(0, 0, size.width, size.height), cv::Scalar(0.55, 0.57, 0.58), 1);
  if (rng.uniform(0, 2)) {  // switch rocker
    cv::rectangle(out, cv::Rect(size.width / 3, size.height / 4, size.width / 3, size.height / 2),
                  cv::Scalar(0.6, 0.62, 0.63), cv::FILLED);
    cv::line(out, {size.width / 3, size.height / 2}, {2 * size.width / 3, size.height / 2}, cv::Scalar(0.4, 0.4, 0.4), 1);
  } else {  // socket
    cv::circle(out, {size.width / 2, size.height / 2}, std::max(2, size.width / 4), cv::Scalar(0.62, 0.64, 0.65), cv::FILLED);
    cv::circle(out, {size.width / 2 - size.width / 10, size.height / 2}, 1, cv::Scalar(0.1, 0.1, 0.1), cv::FILLED);
    cv::circle(out, {size.width / 2 + size.width / 10, size.height / 2}, 1, cv::Scalar(0.1, 0.1, 0.1), cv::FILLED);
  }
  return out;
}

cv::Mat MakeClock(cv::Size size, cv::RNG& rng) {
  cv::Mat out(size, CV_32FC3, ToScalar(RandomColor(rng, 0.1f, 0.5f)));
  const cv::Point c(size.width / 2, size.height / 2);
  const int r = std::min(size.width, size.height) / 2 - 2;
  cv::circle(out, c, r, cv::Scalar(0.85, 0.85, 0.82), cv::FILLED, cv::LINE_AA);
  cv::circle(out, c, r, cv::Scalar(0.1, 0.1, 0.1), std::max(2, r / 12), cv::LINE_AA);
  for (int k = 0; k < 12; ++k) {
    const double a = k * 3.14159265 / 6.0;
    const cv::Point d(static_cast<int>(r * std::cos(a)), static_cast<int>(r * std::sin(a)));
    cv::line(out, c + d * 0.8, c + d * 0.92, cv::Scalar(0.05, 0.05, 0.05), k % 3 ? 1 : 3, cv::LINE_AA);
  }
  const double hour = rng.uniform(0.0, 6.28), minute = rng.uniform(0.0, 6.28);
  cv::line(out, c, c + cv::Point(static_cast<int>(0.5 * r * std::cos(hour)), static_cast<int>(0.5 * r * std::sin(hour))), cv::Scalar(0.05, 0.05, 0.05), 3, cv::LINE_AA);
  cv::line(out, c, c + cv::Point(static_cast<int>(0.75 * r * std::cos(minute)), static_cast<int>(0.75 * r * std::sin(minute))), cv::Scalar(0.05, 0.05, 0.05), 2, cv::LINE_AA);
  DrawText(out, 1, rng, 0.05f, 0.3f);
  return out;
}

cv::Mat MakeFoliage(cv::Size size, cv::RNG& rng) {
  cv::Mat out(size, CV_32FC3, cv::Scalar(0.04, 0.09, 0.05));
  const int leaves = std::max(10, size.area() / 120);
  for (int i = 0; i < leaves; ++i) {
    const cv::Point p(rng.uniform(0, size.width), rng.uniform(0, size.height));
    const cv::Vec3f green(rng.uniform(0.02f, 0.12f), rng.uniform(0.12f, 0.4f), rng.uniform(0.03f, 0.18f));
    cv::ellipse(out, p, cv::Size(rng.uniform(4, 14), rng.uniform(2, 6)), rng.uniform(0.0, 180.0), 0, 360,
                ToScalar(green), cv::FILLED, cv::LINE_AA);
    cv::line(out, p, p + cv::Point(rng.uniform(-8, 9), rng.uniform(-8, 9)), ToScalar(green * 0.5f), 1, cv::LINE_AA);
  }
  return out;
}

}  // namespace

double TexelSizeM(TextureKind kind) {
  switch (kind) {
    case TextureKind::kPaint: return 0.02;
    case TextureKind::kCeiling: return 0.04;
    case TextureKind::kWoodFloor: return 0.008;
    case TextureKind::kWood: return 0.008;
    case TextureKind::kCounter: return 0.008;
    case TextureKind::kTiles: return 0.008;
    case TextureKind::kFabric: return 0.008;
    case TextureKind::kRug: return 0.008;
    case TextureKind::kBooks: return 0.004;
    case TextureKind::kPicture: return 0.004;
    case TextureKind::kPoster: return 0.004;
    case TextureKind::kDocking: return 0.003;
    case TextureKind::kDoor: return 0.01;
    case TextureKind::kWindow: return 0.01;
    case TextureKind::kLampShade: return 0.02;
    case TextureKind::kCabinet: return 0.004;
    case TextureKind::kRadiator: return 0.004;
    case TextureKind::kCurtain: return 0.006;
    case TextureKind::kScreen: return 0.006;
    case TextureKind::kPackaging: return 0.002;
    case TextureKind::kWallpaper: return 0.004;
    case TextureKind::kSwitch: return 0.002;
    case TextureKind::kClock: return 0.002;
    case TextureKind::kFoliage: return 0.004;
  }
  return 0.02;
}

namespace {

// Wood floor planks (with joints across their length), furniture wood or a
// worktop: planks of their own tone with grain; the joints are grooves.
cv::Mat MakeWoodPlanks(const TextureRequest& request, const cv::Vec3f& base, cv::Size size, cv::RNG& rng,
                       ReliefCanvas& relief) {
  const bool floor = request.kind == TextureKind::kWoodFloor;
  const int plank = floor ? 18 : 40;  // texels across a plank
  cv::Mat grain = ValueNoise(cv::Size(size.width, std::max(2, size.height / 12)), 6.0, rng);
  cv::resize(grain, grain, size, 0, 0, cv::INTER_LINEAR);
  cv::Mat fine = ValueNoise(size, 2.0, rng);
  cv::Mat out(size, CV_32FC3);
  for (int r = 0; r < size.height; ++r) {
    cv::Vec3f* o = out.ptr<cv::Vec3f>(r);
    for (int c = 0; c < size.width; ++c) {
      const int plank_index = c / plank;
      const float tone = 0.75f + 0.5f * static_cast<float>((DeriveSeed(request.seed, plank_index) % 1000)) / 1000.0f;
      const int joint_offset = static_cast<int>(DeriveSeed(request.seed + 7, plank_index) % 200);
      const bool joint = (c % plank == 0) || (floor && (r + joint_offset) % 150 == 0);
      const float g = 1.0f + 0.25f * grain.at<float>(r, c) + 0.08f * fine.at<float>(r, c);
      o[c] = joint ? base * 0.35f : base * tone * g;
      if (joint) relief.AddRect(cv::Rect(c, r, 1, 1), -0.003);  // the joints' bevelled grooves
    }
  }
  return out;
}

// Square tiles with grout lines, the grout 3 mm back.
cv::Mat MakeTiles(cv::Size size, const cv::Vec3f& base, cv::RNG& rng, ReliefCanvas& relief) {
  cv::Mat out = Modulated(size, base, ValueNoise(size, 4.0, rng), 0.05f);
  const int tile = 19;
  for (int x = 0; x < size.width; x += tile) cv::line(out, {x, 0}, {x, size.height}, cv::Scalar::all(0.35), 1);
  for (int y = 0; y < size.height; y += tile) cv::line(out, {0, y}, {size.width, y}, cv::Scalar::all(0.35), 1);
  for (int x = 0; x < size.width; x += tile) relief.GrooveColumn(x, 0.003);  // grout, 3 mm back
  for (int y = 0; y < size.height; y += tile) relief.GrooveRow(y, 0.003);
  return out;
}

// Woven fabric; a rug adds a bordered pattern.
cv::Mat MakeFabric(const TextureRequest& request, const cv::Vec3f& base, cv::Size size, cv::RNG& rng) {
  cv::Mat out = Modulated(size, base, ValueNoise(size, 1.5, rng), 0.12f);
  if (request.kind == TextureKind::kRug) {
    const cv::Vec3f accent = RandomColor(rng, 0.05f, 0.6f);
    for (int k = 1; k < 6; ++k) {
      const int m = k * std::min(size.width, size.height) / 14;
      cv::rectangle(out, cv::Rect(m, m, size.width - 2 * m, size.height - 2 * m), ToScalar(accent), 3);
    }
    DrawRandomShapes(out, 25, rng, 0.05f, 0.6f);
  }
  return out;
}

// A framed picture, poster or the docking picture: shapes, gradients and
// text, or one of the user's images.
cv::Mat MakePrint(const TextureRequest& request, const std::vector<cv::Mat>& user_images, cv::Size size,
                  cv::RNG& rng) {
  cv::Mat out = user_images.empty() || request.kind == TextureKind::kDocking
                    ? GradientBackground(size, rng)
                    : UserPicture(size, user_images, rng);
  if (user_images.empty() || request.kind == TextureKind::kDocking) {
    const int shapes = request.kind == TextureKind::kDocking ? 220 : 40;
    DrawRandomShapes(out, shapes, rng, 0.02f, 0.85f);
    DrawText(out, request.kind == TextureKind::kPicture ? 1 : 5, rng, 0.01f, 0.9f);
  }
  AddFrame(out, request.kind == TextureKind::kPoster ? cv::Vec3f(0.8f, 0.8f, 0.8f) : cv::Vec3f(0.05f, 0.06f, 0.08f));
  return out;
}

// A painted door with two recessed panels and a knob.
cv::Mat MakeDoor(cv::Size size, const cv::Vec3f& base, cv::RNG& rng, ReliefCanvas& relief) {
  cv::Mat out = Modulated(size, base, ValueNoise(size, 8.0, rng), 0.03f);
  const int m = size.width / 8;
  cv::rectangle(out, cv::Rect(m, m, size.width - 2 * m, size.height / 2 - m), ToScalar(base * 0.7f), 2);
  cv::rectangle(out, cv::Rect(m, size.height / 2 + m / 2, size.width - 2 * m, size.height / 2 - 2 * m), ToScalar(base * 0.7f), 2);
  relief.AddRect(cv::Rect(m, m, size.width - 2 * m, size.height / 2 - m), -0.004);  // recessed panels
  relief.AddRect(cv::Rect(m + 1, m + 1, size.width - 2 * m - 2, size.height / 2 - m - 2), -0.004);
  relief.AddRect(cv::Rect(m, size.height / 2 + m / 2, size.width - 2 * m, size.height / 2 - 2 * m), -0.004);
  relief.AddRect(cv::Rect(m + 1, size.height / 2 + m / 2 + 1, size.width - 2 * m - 2, size.height / 2 - 2 * m - 2), -0.004);
  cv::circle(out, cv::Point(size.width - m / 2 - 2, size.height / 2), std::max(2, m / 3), cv::Scalar(0.5, 0.55, 0.6), cv::FILLED);
  return out;
}

// The albedo of a request; draws the relief that follows the albedo's own
// structure (joints, grout, spines, panels, fins, folds) into `relief`.
cv::Mat MakeAlbedo(const TextureRequest& request, const std::vector<cv::Mat>& user_images, cv::Size size,
                   ReliefCanvas& relief) {
  cv::RNG rng(request.seed | 1);
  const cv::Vec3f base = request.base_bgr;
  switch (request.kind) {
    case TextureKind::kPaint:
      return Modulated(size, base, ValueNoise(size, 12.0, rng) * 0.6 + ValueNoise(size, 3.0, rng) * 0.4, 0.06f);
    case TextureKind::kCeiling:
      return Modulated(size, base, ValueNoise(size, 10.0, rng), 0.02f);
    case TextureKind::kWoodFloor:
    case TextureKind::kWood:
    case TextureKind::kCounter: return MakeWoodPlanks(request, base, size, rng, relief);
    case TextureKind::kTiles: return MakeTiles(size, base, rng, relief);
    case TextureKind::kFabric:
    case TextureKind::kRug: return MakeFabric(request, base, size, rng);
    case TextureKind::kBooks: return MakeBooks(size, rng, relief);
    case TextureKind::kPicture:
    case TextureKind::kPoster:
    case TextureKind::kDocking: return MakePrint(request, user_images, size, rng);
    case TextureKind::kDoor: return MakeDoor(size, base, rng, relief);
    case TextureKind::kWindow: return MakeWindow(size, rng);
    case TextureKind::kLampShade:
      return Modulated(size, base, ValueNoise(size, 3.0, rng), 0.05f);
    case TextureKind::kCabinet: return MakeCabinet(size, base, rng, relief);
    case TextureKind::kRadiator: return MakeRadiator(size, base, rng, relief);
    case TextureKind::kCurtain: return MakeCurtain(size, base, rng, relief);
    case TextureKind::kScreen: return MakeScreen(size, rng);
    case TextureKind::kPackaging: return MakePackaging(size, base, rng);
    case TextureKind::kWallpaper: return MakeWallpaper(size, base, rng);
    case TextureKind::kSwitch: return MakeSwitch(size, rng);
    case TextureKind::kClock: return MakeClock(size, rng);
    case TextureKind::kFoliage: return MakeFoliage(size, rng);
  }
  return cv::Mat(size, CV_32FC3, ToScalar(base));
}

// Whether a kind has relief at all; prints, glass, screens and lamp shades are flat.
bool HasRelief(TextureKind kind) {
  switch (kind) {
    case TextureKind::kPicture:
    case TextureKind::kPoster:
    case TextureKind::kDocking:
    case TextureKind::kWindow:
    case TextureKind::kLampShade:
    case TextureKind::kScreen:
    case TextureKind::kPackaging:
    case TextureKind::kSwitch:
    case TextureKind::kClock:
      return false;
    default:
      return true;
  }
}

// The material's random relief (amplitude, cell size): plaster waviness and
// paint stipple, wood grain, uneven tiles, weave and wrinkles, rug pile,
// embossed wallpaper, leaves.
void AddMaterialNoise(TextureKind kind, ReliefCanvas& relief, cv::RNG& rng) {
  switch (kind) {
    case TextureKind::kPaint:
      relief.AddNoise(0.002, 0.25, rng);   // plaster waviness
      relief.AddNoise(0.0006, 0.03, rng);  // roller stipple
      break;
    case TextureKind::kCeiling:
      relief.AddNoise(0.001, 0.3, rng);
      relief.AddNoise(0.0004, 0.06, rng);
      break;
    case TextureKind::kWoodFloor:
    case TextureKind::kWood:
    case TextureKind::kCounter: relief.AddNoise(0.0003, 0.016, rng); break;  // brushed grain
    case TextureKind::kTiles: relief.AddNoise(0.0008, 0.05, rng); break;  // uneven glaze
    case TextureKind::kFabric:
      relief.AddNoise(0.0015, 0.012, rng);  // weave
      relief.AddNoise(0.008, 0.06, rng);    // wrinkles and puffiness
      break;
    case TextureKind::kRug:
      relief.AddNoise(0.003, 0.008, rng);  // pile
      relief.AddNoise(0.005, 0.05, rng);
      break;
    case TextureKind::kDoor: relief.AddNoise(0.0005, 0.03, rng); break;
    case TextureKind::kCurtain: relief.AddNoise(0.002, 0.02, rng); break;
    case TextureKind::kWallpaper: relief.AddNoise(0.001, 0.008, rng); break;  // embossing
    case TextureKind::kFoliage: relief.AddNoise(0.010, 0.008, rng); break;  // leaves at every angle
    default: break;
  }
}

}  // namespace

SurfaceTexture MakeTexture(const TextureRequest& request, const std::vector<cv::Mat>& user_images,
                           const PhotoMaterial* photo) {
  SLAM_CHECK(photo == nullptr || photo->kind == request.kind);
  const double texel = photo != nullptr ? photo->texel_m : TexelSizeM(request.kind);
  const cv::Size size(TexelCount(request.size_u_m, texel), TexelCount(request.size_v_m, texel));
  const bool relief_on = request.relief_scale > 0.0 && HasRelief(request.kind);
  ReliefCanvas relief = relief_on ? ReliefCanvas(size, texel) : ReliefCanvas();
  SurfaceTexture out;
  out.albedo = photo != nullptr ? PhotoAlbedo(*photo, request, size, relief)
                                : MakeAlbedo(request, user_images, size, relief);
  if (relief_on) {
    cv::RNG relief_rng(DeriveSeed(request.seed, 0x72656c696566ull) | 1);  // its own stream: "relief"
    AddMaterialNoise(request.kind, relief, relief_rng);
    out.height_m = relief.height_m() * request.relief_scale;
  }
  return out;
}

std::vector<cv::Mat> LoadUserTextures(const std::string& folder) {
  SLAM_THROW_IF_NOT(InputError, IsDirectoryPath(folder)) << folder << ": textures folder does not exist";
  std::vector<std::string> paths;
  for (const std::filesystem::path& entry : SortedFolderEntries(folder)) {
    std::string ext = entry.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") paths.push_back(entry.string());
  }
  // Every image the folder offers is used or refused by name: one skipped
  // without a word would change the dataset unseen. (Files of other
  // extensions are not images to it: docs/synthetic_dataset.md.)
  std::vector<cv::Mat> images;
  for (const std::string& path : paths) {
    CheckImageFileBeforeDecoding(path);  // type, size and truncation before decoding
    cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
    SLAM_THROW_IF_NOT(InputError, !image.empty())
        << path << ": cannot read this --textures image (unreadable or corrupt; fix or remove it)";
    images.push_back(image);
  }
  SLAM_THROW_IF_NOT(InputError, !images.empty()) << folder << ": no .png/.jpg image";
  return images;
}

}  // namespace duskmap
