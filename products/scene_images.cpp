#include "products/scene_images.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "drivers/image/png.h"
#include "sim/seabed/sediment.h"
#include "units/angles.h"

namespace sonarloop::products {
namespace {

std::size_t at(const SceneImages& img, int r, int c) {
  return static_cast<std::size_t>(r) * static_cast<std::size_t>(img.cols) +
         static_cast<std::size_t>(c);
}

// north-up image index of lattice sample (r, c)
std::size_t pixel(const SceneImages& img, int r, int c) {
  return at(img, img.rows - 1 - r, c);
}

}  // namespace

std::array<int, 3> sediment_colour(int id) {
  const auto& info = seabed::sediment_table()[static_cast<std::size_t>(id)];
  if (!info.mz_phi) return id == 2 ? std::array{150, 130, 110} : std::array{125, 125, 130};
  // grain size from gravel (-1 phi) to clay (9 phi): warm sand to dark olive mud
  const double t = std::clamp((*info.mz_phi + 1.0) / 10.0, 0.0, 1.0);
  const auto mix = [t](double a, double b) { return static_cast<int>(a + (b - a) * t); };
  if (t < 0.45) {
    const double u = t / 0.45;
    return {static_cast<int>(165 + 70 * u), static_cast<int>(125 + 85 * u),
            static_cast<int>(80 + 75 * u)};
  }
  return {mix(300, 60), mix(290, 75), mix(200, 55)};
}

std::vector<int> sediments_present(const SceneImages& img) {
  std::set<int> ids(img.sediment.begin(), img.sediment.end());
  return {ids.begin(), ids.end()};
}

void draw_targets(const scene::Scene& s, const scene::SceneView* view, SceneImages& img) {
  img.display_m = img.elevation_m;
  img.target.assign(img.elevation_m.size(), 0);
  const double depth = s.desc().water.depth_m;
  for (const auto& t : s.targets()) {
    const auto& b = t.bounds_W;
    std::shared_ptr<const scene::SceneView> own;
    const scene::SceneView* v = view;
    if (!v || b.min().x() < v->region().min.x() || b.max().x() > v->region().max.x() ||
        b.min().y() < v->region().min.y() || b.max().y() > v->region().max.y()) {
      own = s.view(scene::Box2{Vec2(b.min().x() - 1, b.min().y() - 1),
                               Vec2(b.max().x() + 1, b.max().y() + 1)});
      v = own.get();
    }
    const int r0 =
        std::max(0, static_cast<int>(std::floor((b.min().x() - img.origin_m.x()) / img.spacing_m)));
    const int r1 =
        std::min(img.rows - 1,
                 static_cast<int>(std::ceil((b.max().x() - img.origin_m.x()) / img.spacing_m)));
    const int c0 =
        std::max(0, static_cast<int>(std::floor((b.min().y() - img.origin_m.y()) / img.spacing_m)));
    const int c1 =
        std::min(img.cols - 1,
                 static_cast<int>(std::ceil((b.max().y() - img.origin_m.y()) / img.spacing_m)));
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) {
        const Vec3 o(img.origin_m.x() + r * img.spacing_m, img.origin_m.y() + c * img.spacing_m,
                     b.min().z() - 1.0);
        const auto hit = v->intersect(o, Vec3(0, 0, 1), 10.0);
        if (hit.kind != scene::HitKind::kTarget) continue;
        img.display_m[at(img, r, c)] = static_cast<float>(depth - hit.point_W.z());
        img.target[at(img, r, c)] = 1;
      }
    }
  }
}

std::pair<double, double> write_heightmap_png(const std::string& path, const SceneImages& img) {
  const auto [lo, hi] = std::minmax_element(img.elevation_m.begin(), img.elevation_m.end());
  const double mn = *lo;
  const double mx = std::max(*hi, *lo + 1e-6f);
  std::vector<std::uint16_t> px(img.elevation_m.size());
  for (int r = 0; r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) {
      const double v = (img.elevation_m[at(img, r, c)] - mn) / (mx - mn);
      px[pixel(img, r, c)] =
          static_cast<std::uint16_t>(std::lround(std::clamp(v, 0.0, 1.0) * 65535.0));
    }
  }
  image::write_png_gray16(path, img.cols, img.rows, px);
  return {mn, mx};
}

void write_sediments_png(const std::string& path, const SceneImages& img) {
  std::vector<std::uint8_t> rgb(3 * img.sediment.size());
  for (int r = 0; r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) {
      const auto col = sediment_colour(img.sediment[at(img, r, c)]);
      const std::size_t p = 3 * pixel(img, r, c);
      for (int k = 0; k < 3; ++k)
        rgb[p + static_cast<std::size_t>(k)] =
            static_cast<std::uint8_t>(std::clamp(col[k], 0, 255));
    }
  }
  image::write_png_rgb8(path, img.cols, img.rows, rgb);
}

void write_relief_png(const std::string& path, const SceneImages& img) {
  constexpr double kExaggeration = 3.0;
  constexpr double kSunAzimuth = 315.0 * kRadPerDeg;  // from the north-west
  constexpr double kSunAltitude = 45.0 * kRadPerDeg;
  // sun direction in (north, east, up)
  const Vec3 sun(std::cos(kSunAltitude) * std::cos(kSunAzimuth),
                 std::cos(kSunAltitude) * std::sin(kSunAzimuth), std::sin(kSunAltitude));
  const auto h = [&](int r, int c) {
    r = std::clamp(r, 0, img.rows - 1);
    c = std::clamp(c, 0, img.cols - 1);
    return kExaggeration * img.display_m[at(img, r, c)];
  };
  std::vector<std::uint8_t> rgb(3 * img.display_m.size());
  for (int r = 0; r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) {
      const double dzdn = (h(r + 1, c) - h(r - 1, c)) / (2.0 * img.spacing_m);
      const double dzde = (h(r, c + 1) - h(r, c - 1)) / (2.0 * img.spacing_m);
      const Vec3 normal = Vec3(-dzdn, -dzde, 1.0).normalized();
      const double shade = 0.25 + 0.75 * std::max(0.0, normal.dot(sun));
      const std::array<int, 3> base = img.target[at(img, r, c)]
                                          ? std::array{230, 40, 30}
                                          : sediment_colour(img.sediment[at(img, r, c)]);
      const std::size_t p = 3 * pixel(img, r, c);
      for (int k = 0; k < 3; ++k) {
        rgb[p + static_cast<std::size_t>(k)] =
            static_cast<std::uint8_t>(std::clamp(base[k] * shade, 0.0, 255.0));
      }
    }
  }
  image::write_png_rgb8(path, img.cols, img.rows, rgb);
}

}  // namespace sonarloop::products
